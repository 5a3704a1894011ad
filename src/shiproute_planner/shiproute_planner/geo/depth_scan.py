"""Capped shallowest-depth scans of many legs at once, as the optimiser needs them: open water
crossed in jumps (clear distances to the nearest block shallower than a depth level), legs
split over the planner's threads. The shallows found are those of
`Bathymetry.segment_min_depth_m` (same samples); a leg that meets known water only where it
jumps may read NaN (no depth met) where the plain walk reads its cap, and the reverse:
neither constrains the leg.
"""

from __future__ import annotations

import threading
import weakref
from collections.abc import Callable

import numpy as np

from ..chunks import in_chunks
from . import _depth_kernels as dk
from .clear_distance import banded_clear_distance_deg
from .depth import Bathymetry

# depth levels [m] a clear-distance raster is built for (one per level met, on first use):
# a scan uses the smallest level at or above every cap it is given
LEVELS_M = (12.0, 15.0, 18.0, 22.0, 27.0, 33.0, 40.0, 50.0, 65.0, 85.0, 110.0, 150.0)
CLEAR_FACTOR = 4  # clear distances on blocks of 4 x 4 pre-check blocks (1 deg)
MIN_CHUNK = 64  # legs per thread below which one thread scans them all

_LOCK = threading.Lock()
_CLEAR: weakref.WeakKeyDictionary[Bathymetry, dict[float, np.ndarray]] = (
    weakref.WeakKeyDictionary())
_CELL_MIN: weakref.WeakKeyDictionary[Bathymetry, np.ndarray] = weakref.WeakKeyDictionary()
NO_CELL_MIN = np.full((1, 1), 255, dtype=np.uint8)
ROWS_PER_PASS = 256  # rows of a (memory-mapped) grid read at a time


def level_for(cap_m: float) -> float | None:
    """The smallest depth level at or above `cap_m` (None: above every level, or NaN)."""
    for level in LEVELS_M:
        if cap_m <= level:
            return level
    return None


def clear_raster(bathymetry: Bathymetry, level_m: float) -> np.ndarray:
    """Per `CLEAR_FACTOR` x `CLEAR_FACTOR` pre-check blocks: lower bound of the arc [deg] to
    the nearest pre-check block with a known depth below `level_m` (unknown water, such as a
    coarse grid's land and coast, is crossed too; built once per bathymetry and level, in
    milliseconds on the coarser raster)."""
    with _LOCK:
        cached = _CLEAR.setdefault(bathymetry, {})
        if level_m not in cached:
            coarse, block_deg = bathymetry.block_minimum
            flagged = coarse < level_m  # known shallower than the level (+inf: unknown)
            r, c = flagged.shape
            f = CLEAR_FACTOR
            big = np.asarray(flagged[: r - r % f, : c - c % f].reshape(r // f, f, c // f, f)
                             .any(axis=(1, 3)))
            cached[level_m] = banded_clear_distance_deg(big, f * block_deg)
        return cached[level_m]


def cell_minimum(bathymetry: Bathymetry) -> np.ndarray:
    """One grid: per cell, the floor of the shallowest known depth [m] in its 3 x 3
    neighbourhood as uint8 (254: 254 m or more, 255: none known), the shelf walk's jump
    test (a quarter of the grid's float32 size). Several grids: `NO_CELL_MIN` (the depth of
    a point comes from whichever grid knows it, so the walk samples every point)."""
    from scipy.ndimage import minimum_filter

    from . import depth_cache

    if len(bathymetry.grids) != 1:
        return NO_CELL_MIN
    with _LOCK:
        if bathymetry not in _CELL_MIN:
            grid = bathymetry.grids[0]
            d = grid.depth_m
            floor = np.empty(d.shape, dtype=np.uint8)
            for a in range(0, d.shape[0], ROWS_PER_PASS):
                part = np.asarray(d[a:a + ROWS_PER_PASS], dtype=np.float32)
                floor[a:a + ROWS_PER_PASS] = np.where(
                    np.isnan(part), 255, np.clip(np.floor(np.nan_to_num(part)), 0, 254))
            depth_cache.drop_resident_pages(d)  # the pass read all of a mapped grid
            mode = ("nearest", "wrap" if grid.periodic else "nearest")
            _CELL_MIN[bathymetry] = np.ascontiguousarray(minimum_filter(floor, size=3,
                                                                        mode=mode))
        return _CELL_MIN[bathymetry]


def prepare(bathymetry: Bathymetry, lowest_need_m: float, highest_need_m: float) -> None:
    """Build ahead the rasters scans needing lowest..highest_need_m will use (the cell minima
    and the clear distances of those levels), so a plan's search does not pay for them."""
    cell_minimum(bathymetry)
    for level in LEVELS_M:
        if level >= lowest_need_m:
            clear_raster(bathymetry, level)
        if level >= highest_need_m:
            break


def capped_scan(bathymetry: Bathymetry, lon0: np.ndarray, lat0: np.ndarray,
                lon1: np.ndarray, lat1: np.ndarray, cap_m: np.ndarray
                ) -> tuple[np.ndarray, Callable[[int, int], None] | None]:
    """`capped_min_depth_m` as a job: the flat output and the work that fills legs a..b of
    it (None: the plain walk has filled it already), for a caller that runs it over its own
    threads together with other per-leg work."""
    shape = np.shape(lon0)
    x0, y0, x1, y1 = (np.ascontiguousarray(a, dtype=float).ravel()
                      for a in (lon0, lat0, lon1, lat1))
    cap = np.ascontiguousarray(np.broadcast_to(cap_m, shape), dtype=float).ravel()
    finite = cap[np.isfinite(cap)]
    level = level_for(float(finite.max())) if finite.size else None
    if level is None:  # nothing to jump with: the plain walk
        plain = bathymetry.segment_min_depth_m(lon0, lat0, lon1, lat1, cap_m)
        return np.asarray(plain, dtype=float).ravel(), None
    out = np.empty(x0.size)
    clear = clear_raster(bathymetry, level)
    data, table = bathymetry.kernel_grids
    coarse, block_deg = bathymetry.block_minimum
    cell_min = cell_minimum(bathymetry)

    def scan(a: int, b: int) -> None:
        dk.segment_min_depth_skip(x0[a:b], y0[a:b], x1[a:b], y1[a:b], cap[a:b], data, table,
                                  coarse, block_deg, clear, CLEAR_FACTOR * block_deg, level,
                                  cell_min, out[a:b])

    return out, scan


def capped_min_depth_m(bathymetry: Bathymetry, lon0: np.ndarray, lat0: np.ndarray,
                       lon1: np.ndarray, lat1: np.ndarray, cap_m: np.ndarray) -> np.ndarray:
    """Shallowest depth [m] along each great-circle leg, capped at its finite `cap_m` (the
    depth the leg needs); NaN where no grid covers the leg. Shapes as the inputs."""
    out, scan = capped_scan(bathymetry, lon0, lat0, lon1, lat1, cap_m)
    if scan is not None:
        in_chunks(out.size, scan, MIN_CHUNK)
    return out.reshape(np.shape(lon0))
