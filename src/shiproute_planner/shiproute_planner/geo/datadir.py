"""Where derived data (land rasters, seed pools) is cached: $SHIPROUTE_DATA_DIR or ~/.cache."""

from __future__ import annotations

import os
from pathlib import Path


def data_dir() -> Path:
    """The shiproute data directory, created on first use."""
    env = os.environ.get("SHIPROUTE_DATA_DIR")
    path = Path(env) if env else Path.home() / ".cache" / "shiproute"
    path.mkdir(parents=True, exist_ok=True)
    return path
