"""Where derived data (land rasters, seed pools) is cached: $SHIPROUTE_DATA_DIR or ~/.cache."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np


def data_dir() -> Path:
    """The shiproute data directory, created on first use."""
    env = os.environ.get("SHIPROUTE_DATA_DIR")
    path = Path(env) if env else Path.home() / ".cache" / "shiproute"
    path.mkdir(parents=True, exist_ok=True)
    return path


def load_npz(path: Path, *names: str) -> tuple[np.ndarray, ...] | None:
    """The arrays `names` of a cache file read whole, or None when it is missing, corrupt or
    lacks one of them (the caller rebuilds what it caches)."""
    try:
        with np.load(path) as z:
            return tuple(np.asarray(z[n]) for n in names)
    except (OSError, ValueError, KeyError):
        return None


def save_npz_atomic(path: Path, **arrays: np.ndarray) -> bool:
    """Store `arrays` in `path` by atomic replace, so a reader never sees half a file; False
    (nothing stored) when the data directory is read-only: the caller keeps them in memory."""
    tmp = path.with_suffix(f".{os.getpid()}.tmp.npz")
    try:
        np.savez(tmp, **arrays)  # type: ignore[arg-type]  # stubs type **kwds like allow_pickle
        os.replace(tmp, path)
    except OSError:
        tmp.unlink(missing_ok=True)
        return False
    return True
