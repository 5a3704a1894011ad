"""Land mask used by the planner: cached raster pre-check + exact GSHHG test near coasts.

The raster (default 0.05 deg) is built once per GSHHG resolution and cell size and cached as a
.npy file in the shiproute data directory. Samples in sea or land cells are decided by the
raster; samples in coastal cells are tested exactly against the polygons.
"""

from __future__ import annotations

import functools
import os
from collections.abc import Callable
from pathlib import Path
from typing import cast

import numpy as np

from .coast_distance import COAST_DISTANCE_VERSION, coast_distance
from .datadir import data_dir
from .fine_coast import FineCoast
from .gshhg import load_land_polygons
from .land_kernels import raster_lookup, scan_segments
from .landexact import ExactLand
from .raster import COAST, LAND, build_land_raster

RASTER_VERSION = 1
FINE_FACTOR = 5  # fine cells per raster cell side in coastal cells (0.01 deg, ~1.1 km)


class LandMask:
    """Land tests of points and great-circle segments (longitudes in any 360-degree frame)."""

    def __init__(
        self, resolution: str = "i", cell_deg: float = 0.05, cache_dir: Path | None = None
    ) -> None:
        self.resolution = resolution
        self.cell_deg = float(cell_deg)
        self.polygons = load_land_polygons(resolution)
        self.raster = self._load_or_build(cache_dir or data_dir())
        # GA offspring share most legs with their parents (same genes -> same nodes), so
        # exact results per segment are memoised; cleared when it grows past `_cache_max`
        self._seg_cache: dict[bytes, int] = {}
        self._cache_max = 500_000

    @functools.cached_property
    def exact(self) -> ExactLand:
        """The polygons' point test, built on first use: its index of every polygon's box
        (~90 MB at full resolution) is not needed where only the raster is read."""
        return ExactLand(self.polygons)

    def _load_or_build(self, cache_dir: Path) -> np.ndarray:
        self._cache_dir = cache_dir
        return self._cached_array(
            "landmask", lambda: build_land_raster(self.polygons, self.exact, self.cell_deg))

    def _cached_array(self, kind: str, build: Callable[[], np.ndarray]) -> np.ndarray:
        """Array `kind` of this resolution and cell size from the data directory's .npy
        cache (memory-mapped), built and stored atomically when missing or corrupt."""
        path = self._cache_dir / cached_array_name(kind, self.resolution, self.cell_deg)
        if path.is_file():
            try:
                return np.load(path, mmap_mode="r")
            except (OSError, ValueError):
                pass  # corrupt cache: rebuild below
        array = build()
        tmp = path.with_suffix(f".{os.getpid()}.tmp.npy")
        np.save(tmp, array)
        os.replace(tmp, path)
        return array

    @functools.cached_property
    def fine_coast(self) -> FineCoast:
        """Exact verdicts on a ~1 km grid inside coastal cells, resolved as the GA meets them."""
        name = (f"finecoast_v{RASTER_VERSION}_gshhg_{self.resolution}_{self.cell_deg:g}deg"
                f"_{FINE_FACTOR}.npz")
        return FineCoast(np.asarray(self.raster), self.cell_deg, self.exact.contains,
                         FINE_FACTOR, self._cache_dir / name)

    @functools.cached_property
    def sea_distance_cells(self) -> np.ndarray:
        """Chessboard distance [cells] from each raster cell to the nearest land or coastal
        cell (0 on them, at most 255): compiled scans skip open sea with it."""
        return self._cached_array("seadistance", lambda: sea_distance_cells(self.raster))

    @functools.cached_property
    def coast_distance(self) -> np.ndarray:
        """Signed lower bound of each raster cell's distance to the coast [0.1 NM] (sea > 0,
        land < 0, coast 0; `geo.coast_distance`): the land walk's jumps."""
        return self._cached_array(f"coastdistance{COAST_DISTANCE_VERSION}",
                                  lambda: coast_distance(self.raster, self.cell_deg))

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

    def segment_land_samples(
        self,
        lon0: np.ndarray,
        lat0: np.ndarray,
        lon1: np.ndarray,
        lat1: np.ndarray,
        spacing_deg: float | None = None,
    ) -> np.ndarray:
        """Number of samples on land along each great-circle segment (0 = clear)."""
        shape = np.shape(lon0)
        spacing = float(spacing_deg or self.cell_deg)
        tag = spacing  # memo entries per sample spacing
        ends = np.stack([np.asarray(a, dtype=float).ravel() for a in (lon0, lat0, lon1, lat1)],
                        axis=1)
        ends = np.ascontiguousarray(np.append(ends, np.full((ends.shape[0], 1), tag), 1))
        rows = ends.view(np.dtype((np.void, ends.dtype.itemsize * 5))).ravel()
        keys = cast(list[bytes], rows.tolist())  # one opaque bytes key per segment row
        cache = self._seg_cache
        out = np.array([cache.get(k, -1) for k in keys], dtype=np.int64)
        todo = np.flatnonzero(out < 0)
        if todo.size:
            fresh = self._scan(ends[todo, :4], spacing)
            out[todo] = fresh
            if len(cache) > self._cache_max:
                cache.clear()
            cache.update(zip([keys[i] for i in todo], fresh.tolist(), strict=True))
        return out.reshape(shape)

    def _scan(self, ends: np.ndarray, spacing: float) -> np.ndarray:
        """Land samples of segments given as rows (lon0, lat0, lon1, lat1)."""
        x0, y0, x1, y1 = (np.ascontiguousarray(ends[:, i]) for i in range(4))
        n_seg = x0.size
        land = np.zeros(n_seg, dtype=np.int64)
        cap = max(1024, 64 * n_seg)
        raster = np.asarray(self.raster)
        while True:
            c_lon, c_lat = np.empty(cap), np.empty(cap)
            c_seg = np.empty(cap, dtype=np.int64)
            n = scan_segments(x0, y0, x1, y1, raster, self.cell_deg, spacing, land,
                              c_lon, c_lat, c_seg)
            if n >= 0:
                break
            cap *= 4
        if n:
            hit = self.exact.contains(c_lon[:n], c_lat[:n])
            land += np.bincount(c_seg[:n][hit], minlength=n_seg)
        return land


def cached_array_name(kind: str, resolution: str, cell_deg: float) -> str:
    """File name of a land mask's cached array `kind` in the data directory."""
    return f"{kind}_v{RASTER_VERSION}_gshhg_{resolution}_{cell_deg:g}deg.npy"


def land_raster_built(resolution: str, cell_deg: float = 0.05,
                      cache_dir: Path | None = None) -> bool:
    """True when the land raster of `resolution` is already stored on this machine (its
    first build, ~40 s at full resolution, is then not ahead)."""
    return ((cache_dir or data_dir()) / cached_array_name("landmask", resolution, cell_deg)
            ).is_file()


def coast_distance_built(resolution: str, cell_deg: float = 0.05,
                         cache_dir: Path | None = None) -> bool:
    """True when the level-0 distance to the coast of `resolution` is already stored on this
    machine (its first build takes a few seconds)."""
    kind = f"coastdistance{COAST_DISTANCE_VERSION}"
    return ((cache_dir or data_dir()) / cached_array_name(kind, resolution, cell_deg)).is_file()


def sea_distance_cells(raster: np.ndarray, cap: int = 255) -> np.ndarray:
    """Chessboard distance [cells] to the nearest non-sea cell, wrapping in longitude."""
    from scipy.ndimage import distance_transform_cdt

    r = np.asarray(raster)
    tiled = np.concatenate([r[:, -cap:], r, r[:, :cap]], axis=1)
    d = distance_transform_cdt(tiled == 0, metric="chessboard")[:, cap:-cap]
    return np.ascontiguousarray(np.minimum(d, cap).astype(np.uint8))


@functools.lru_cache(maxsize=2)
def default_land_mask(resolution: str = "i", cell_deg: float = 0.05) -> LandMask:
    """Process-wide shared land mask (loading costs ~0.5 s, building ~3 s once)."""
    return LandMask(resolution, cell_deg)
