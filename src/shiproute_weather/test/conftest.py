"""Tests of shiproute_weather mirror its rooms; the shared fixtures module sits here."""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))  # weather_fixtures for every room
