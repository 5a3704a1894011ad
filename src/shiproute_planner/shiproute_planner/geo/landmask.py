"""Land mask used by the planner: cached raster pre-check + exact GSHHG test near coasts.

The raster (default 0.05 deg) is built once per GSHHG resolution and cell size and cached as a
.npy file in the shiproute data directory. Samples in sea or land cells are decided by the
raster; samples in coastal cells are tested exactly against the polygons.
"""

from __future__ import annotations

import functools
import os
from pathlib import Path

import numpy as np

from ._kernels import raster_lookup, scan_segments
from .datadir import data_dir
from .gshhg import load_land_polygons
from .landexact import ExactLand
from .raster import COAST, LAND, build_land_raster

RASTER_VERSION = 1


class LandMask:
    """Land tests of points and great-circle segments (longitudes in any 360-degree frame)."""

    def __init__(
        self, resolution: str = "i", cell_deg: float = 0.05, cache_dir: Path | None = None
    ) -> None:
        self.resolution = resolution
        self.cell_deg = float(cell_deg)
        self.polygons = load_land_polygons(resolution)
        self.exact = ExactLand(self.polygons)
        self.raster = self._load_or_build(cache_dir or data_dir())
        # GA offspring share most legs with their parents (same genes -> same nodes), so
        # exact results per segment are memoised; cleared when it grows past `_cache_max`
        self._seg_cache: dict[bytes, int] = {}
        self._cache_max = 500_000
        # quantised exact results (see `contains_quantised`): sorted keys and answers
        self._q_keys = np.empty(0, dtype=np.int64)
        self._q_land = np.empty(0, dtype=bool)

    def _load_or_build(self, cache_dir: Path) -> np.ndarray:
        name = f"landmask_v{RASTER_VERSION}_gshhg_{self.resolution}_{self.cell_deg:g}deg.npy"
        path = cache_dir / name
        if path.is_file():
            try:
                return np.load(path, mmap_mode="r")
            except (OSError, ValueError):
                pass  # corrupt cache: rebuild below
        raster = build_land_raster(self.polygons, self.exact, self.cell_deg)
        tmp = path.with_suffix(f".{os.getpid()}.tmp.npy")
        np.save(tmp, raster)
        os.replace(tmp, path)
        return raster

    def is_land(self, lon_deg: np.ndarray, lat_deg: np.ndarray) -> np.ndarray:
        """True where a point is on land (raster, exact in coastal cells)."""
        lon = np.ascontiguousarray(lon_deg, dtype=float).ravel()
        lat = np.ascontiguousarray(lat_deg, dtype=float).ravel()
        cls = raster_lookup(lon, lat, np.asarray(self.raster), self.cell_deg)
        out = cls == LAND
        coast = np.flatnonzero(cls == COAST)
        if coast.size:
            out[coast] = self.exact.contains(lon[coast], lat[coast])
        return out.reshape(np.shape(lon_deg))

    def contains_quantised(self, lon_deg: np.ndarray, lat_deg: np.ndarray,
                           quantum_deg: float) -> np.ndarray:
        """Exact land test of the centre of the `quantum_deg` cell holding each point.

        Answers are kept (sorted array, vectorised lookups), so a GA whose routes sweep the
        same coasts generation after generation pays the polygon test once per fine cell:
        a lazily built fine raster, exact at its cell centres."""
        inv = 1.0 / quantum_deg
        n_lon = round(360.0 * inv)
        i = np.floor((np.asarray(lat_deg, dtype=float) + 90.0) * inv).astype(np.int64)
        j = np.floor(((np.asarray(lon_deg, dtype=float) + 180.0) % 360.0) * inv).astype(np.int64)
        key = i * n_lon + j
        out = np.zeros(key.shape, dtype=bool)
        known = np.zeros(key.shape, dtype=bool)
        if self._q_keys.size:
            pos = np.minimum(np.searchsorted(self._q_keys, key), self._q_keys.size - 1)
            known = self._q_keys[pos] == key
            out[known] = self._q_land[pos[known]]
        if not known.all():
            new = np.unique(key[~known])
            ci, cj = new // n_lon, new % n_lon
            land = self.exact.contains((cj + 0.5) * quantum_deg - 180.0,
                                       (ci + 0.5) * quantum_deg - 90.0)
            keys = np.concatenate([self._q_keys, new])
            vals = np.concatenate([self._q_land, land])
            order = np.argsort(keys, kind="stable")
            self._q_keys, self._q_land = keys[order], vals[order]
            pos = np.searchsorted(self._q_keys, key[~known])
            out[~known] = self._q_land[pos]
        return out

    def segment_land_samples(
        self,
        lon0: np.ndarray,
        lat0: np.ndarray,
        lon1: np.ndarray,
        lat1: np.ndarray,
        spacing_deg: float | None = None,
        quantum_deg: float = 0.0,
    ) -> np.ndarray:
        """Number of samples on land along each great-circle segment (0 = clear).

        `quantum_deg` > 0 tests coastal samples with `contains_quantised` (GA loop) instead
        of exactly at the sample."""
        shape = np.shape(lon0)
        spacing = float(spacing_deg or self.cell_deg)
        tag = spacing if quantum_deg <= 0 else -spacing - quantum_deg  # separate memo entries
        ends = np.stack([np.asarray(a, dtype=float).ravel() for a in (lon0, lat0, lon1, lat1)],
                        axis=1)
        ends = np.ascontiguousarray(np.append(ends, np.full((ends.shape[0], 1), tag), 1))
        keys = ends.view(np.dtype((np.void, ends.dtype.itemsize * 5))).ravel().tolist()
        cache = self._seg_cache
        out = np.array([cache.get(k, -1) for k in keys], dtype=np.int64)
        todo = np.flatnonzero(out < 0)
        if todo.size:
            fresh = self._scan(ends[todo, :4], spacing, quantum_deg)
            out[todo] = fresh
            if len(cache) > self._cache_max:
                cache.clear()
            cache.update(zip([keys[i] for i in todo], fresh.tolist(), strict=True))
        return out.reshape(shape)

    def _scan(self, ends: np.ndarray, spacing: float, quantum_deg: float = 0.0) -> np.ndarray:
        """Land samples of segments given as rows (lon0, lat0, lon1, lat1)."""
        arrays = [np.ascontiguousarray(ends[:, i]) for i in range(4)]
        n_seg = arrays[0].size
        land = np.zeros(n_seg, dtype=np.int64)
        cap = max(1024, 64 * n_seg)
        raster = np.asarray(self.raster)
        while True:
            c_lon, c_lat = np.empty(cap), np.empty(cap)
            c_seg = np.empty(cap, dtype=np.int64)
            n = scan_segments(*arrays, raster, self.cell_deg, spacing, land, c_lon, c_lat, c_seg)
            if n >= 0:
                break
            cap *= 4
        if n and quantum_deg > 0:
            # GA loop: a segment with raster-land samples is on land whatever its coastal
            # samples say, so only clear segments' coastal samples are tested
            keep = land[c_seg[:n]] == 0
            c_lon, c_lat, c_seg = c_lon[:n][keep], c_lat[:n][keep], c_seg[:n][keep]
            n = c_seg.size
        if n:
            if quantum_deg > 0:
                hit = self.contains_quantised(c_lon[:n], c_lat[:n], quantum_deg)
            else:
                hit = self.exact.contains(c_lon[:n], c_lat[:n])
            land += np.bincount(c_seg[:n][hit], minlength=n_seg)
        return land


@functools.lru_cache(maxsize=2)
def default_land_mask(resolution: str = "i", cell_deg: float = 0.05) -> LandMask:
    """Process-wide shared land mask (loading costs ~0.5 s, building ~3 s once)."""
    return LandMask(resolution, cell_deg)
