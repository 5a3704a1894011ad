"""Prepared depth grids kept in the data directory and memory-mapped read-only.

A coarse grid (ETOPO5) takes seconds to prepare (see `geo.bathymetry`); the result is stored
once per source file as `<key>.npy` (float32 depths, NaN unknown) beside `<key>.json` (the
grid's name, origin, spacing and wrap). Opening it maps the file instead of reading it: the
process holds only the pages its lookups touch (a few along a route), they are shared with every
other process mapping the same file, and no NetCDF or xarray import is needed. Pages a full scan
touched (the pre-check raster) are handed back with `drop_resident_pages`.
"""

from __future__ import annotations

import contextlib
import json
import mmap
import os
from pathlib import Path
from typing import Any

import numpy as np

#: the grid description stored beside the depths
META_KEYS = ("name", "lat0_deg", "dlat_deg", "lon0_deg", "dlon_deg", "periodic")


def cache_paths(directory: Path, key: str) -> tuple[Path, Path]:
    """(depths .npy, description .json) of a prepared grid."""
    return directory / f"depth_{key}.npy", directory / f"depth_{key}.json"


def write_prepared(directory: Path, key: str, depth_m: np.ndarray, meta: dict[str, Any]
                   ) -> None:
    """Store a prepared grid atomically (the description last: it marks the pair complete);
    a write that fails leaves nothing behind and is not an error (the grid is prepared again)."""
    npy, desc = cache_paths(directory, key)
    pid = os.getpid()
    tmp_npy, tmp_desc = npy.with_suffix(f".{pid}.tmp.npy"), desc.with_suffix(f".{pid}.tmp")
    try:
        np.save(tmp_npy, np.ascontiguousarray(depth_m, dtype=np.float32))
        os.replace(tmp_npy, npy)
        tmp_desc.write_text(json.dumps({k: meta[k] for k in META_KEYS}))
        os.replace(tmp_desc, desc)
    except OSError:
        for tmp in (tmp_npy, tmp_desc):
            tmp.unlink(missing_ok=True)


def open_prepared(directory: Path, key: str) -> tuple[np.ndarray, dict[str, Any]] | None:
    """(read-only memory-mapped depths [m], description) of a prepared grid, or None when it
    is missing or damaged (then it is prepared again)."""
    npy, desc = cache_paths(directory, key)
    if not (npy.is_file() and desc.is_file()):
        return None
    try:
        meta = json.loads(desc.read_text())
        depth = map_npy(npy)
    except (OSError, ValueError):
        return None
    if not isinstance(meta, dict) or set(META_KEYS) - set(meta) or depth.ndim != 2:
        return None
    return depth, meta


def map_npy(path: Path) -> np.ndarray:
    """A 2-D float32 C-order .npy file as a read-only array over a shared mapping of the file
    (ValueError when the file is not one)."""
    with open(path, "rb") as f:
        version = np.lib.format.read_magic(f)
        if version != (1, 0):
            raise ValueError(f"{path}: .npy format {version} not written by this cache")
        shape, fortran, dtype = np.lib.format.read_array_header_1_0(f)
        offset = f.tell()
        if fortran or dtype != np.float32 or len(shape) != 2:
            raise ValueError(f"{path}: not a 2-D float32 C-order array")
        size = int(np.prod(shape)) * 4
        if os.fstat(f.fileno()).st_size < offset + size:
            raise ValueError(f"{path}: truncated")
        mapped = mmap.mmap(f.fileno(), 0, access=mmap.ACCESS_READ)
    return np.frombuffer(mapped, dtype=np.float32, count=size // 4, offset=offset).reshape(shape)


def drop_resident_pages(array: np.ndarray) -> None:
    """Let go of the pages of a file-mapped array that this process has touched (they are read
    from the file again when needed): a full scan would otherwise leave the whole file resident
    in the process. Does nothing for an array in ordinary memory."""
    base: Any = array
    while base is not None and not isinstance(base, mmap.mmap):
        base = getattr(base, "base", None) if isinstance(base, np.ndarray) else getattr(
            base, "obj", None)
    if isinstance(base, mmap.mmap):
        with contextlib.suppress(OSError, ValueError, AttributeError):
            base.madvise(mmap.MADV_DONTNEED)
