"""Shared fixtures of the shiproute_ais_replay unit tests."""

from __future__ import annotations

from pathlib import Path

import pytest
from ais_replay_helpers import make_states, write_bag
from shiproute_ais_replay.bag.shipstate import ShipStateRecord


@pytest.fixture
def small_bag(tmp_path: Path) -> tuple[Path, list[ShipStateRecord]]:
    """A 200-state bag directory (ShipState + NavSatFix)."""
    states = make_states(200)
    return write_bag(tmp_path / "voyage", states), states
