"""Distance to the full-resolution coastline on a fine grid, per 0.5-deg tile, built lazily
(level 1, where the 0.05-deg level 0 of `geo.coast_distance` cannot decide).

Each tile holds `FINE_PER_TILE` x `FINE_PER_TILE` cells (0.0025 deg, ~280 m) of one uint8:
0 for cells on land or touching the coastline, else 1 + a lower bound of the distance from any
point of the cell to land in `UNIT_NM` steps, capped at `CAP_NM`. A tile is built from the
land clipped to the tile padded by the cap: the coastline, sampled every `SAMPLE_CELLS`
cells, marks the cells its samples fall in (a band one cell wide, so channels a few cells
wide stay open); each connected patch of other cells is land or sea by one exact point test
(a coastline stretch between two samples can cut the corner of a patch cell by at most half
the sample spacing, ~30 m); sea cells get scipy's Euclidean distance to the band (longitude
spacing shrunk by the cosine of the padded tile's most poleward latitude: a lower bound
within the padding), minus a cell diagonal and half the sample spacing. Tiles are kept in a
slot map (tile row, column -> slot) that a compiled walk reads, and saved in the data
directory (`save`) so a machine builds each once.
"""

from __future__ import annotations

import math
import os
import threading
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

from .coast_distance import NM_PER_DEG
from .datadir import load_npz, save_npz_atomic
from .raster import patch_representatives

FINE_DISTANCE_VERSION = 2  # in the cache file name: bump when the tiles change
TILE_DEG = 0.5
FINE_PER_TILE = 200  # cells per tile side: 0.0025 deg
UNIT_NM = 0.05  # distance step of the stored values
SAMPLE_CELLS = 0.2  # coastline sample spacing [cells]: no coastline point is farther from one
CAP_NM = 6.0  # the largest distance stored: above the largest clearance a plan may ask (5 NM)
TILE_ROWS, TILE_COLS = round(180.0 / TILE_DEG), round(360.0 / TILE_DEG)
PART_MARK = "_part"  # part files: <cache file stem>_part<pid>-<ns>.npz
MAX_PARTS = 16  # part files read before they are merged into the cache file
MIN_ROWS = 64  # rows of the first tile store
LandNear = Callable[[float, float, float, float], list]  # box -> clipped shapely geometries
Contains = Callable[[np.ndarray, np.ndarray], np.ndarray]  # (lon, lat) -> on land


def build_tile(ti: int, tj: int, land_near: LandNear, contains: Contains) -> np.ndarray:
    """uint8 (FINE_PER_TILE, FINE_PER_TILE) grid of tile (row `ti` from 90 S, column `tj`
    from 180 W): 0 on or touching land, else 1 + floor(lower bound of the distance to land
    [NM] / UNIT_NM), at most 1 + CAP_NM / UNIT_NM."""
    import shapely
    from scipy import ndimage

    fine_deg = TILE_DEG / FINE_PER_TILE
    fine_nm = fine_deg * NM_PER_DEG
    lat0, lon0 = -90.0 + ti * TILE_DEG, -180.0 + tj * TILE_DEG
    pad_rows = math.ceil(CAP_NM / fine_nm) + 2
    poleward = min(max(abs(lat0), abs(lat0 + TILE_DEG)) + (pad_rows + 1) * fine_deg, 89.9)
    shrink = math.cos(math.radians(poleward))
    pad_cols = math.ceil(CAP_NM / (fine_nm * shrink)) + 2
    n_r, n_c = FINE_PER_TILE + 2 * pad_rows, FINE_PER_TILE + 2 * pad_cols
    b_lat0, b_lon0 = lat0 - pad_rows * fine_deg, lon0 - pad_cols * fine_deg
    parts = land_near(b_lon0, b_lat0, b_lon0 + n_c * fine_deg, b_lat0 + n_r * fine_deg)
    band = np.zeros((n_r, n_c), dtype=bool)
    if parts:
        edges = shapely.segmentize(shapely.boundary(np.array(parts, dtype=object)),
                                   SAMPLE_CELLS * fine_deg)
        xy = shapely.get_coordinates(edges)
        r = np.floor((xy[:, 1] - b_lat0) / fine_deg).astype(np.int64)
        c = np.floor((xy[:, 0] - b_lon0) / fine_deg).astype(np.int64)
        ok = (r >= 0) & (r < n_r) & (c >= 0) & (c < n_c)
        band[r[ok], c[ok]] = True
    labels, rep = patch_representatives(~band)
    rep_lat = b_lat0 + (rep // n_c + 0.5) * fine_deg
    rep_lon = b_lon0 + (rep % n_c + 0.5) * fine_deg
    is_land = np.concatenate([[True], np.asarray(contains(rep_lon, rep_lat), dtype=bool)])
    sea = ~is_land[labels]  # label 0 (the band) counts as land
    if band.any():
        d = ndimage.distance_transform_edt(~band, sampling=(fine_nm, fine_nm * shrink))
        d = d - math.hypot(fine_nm, fine_nm * shrink) - 0.5 * SAMPLE_CELLS * fine_nm
    else:
        d = np.full((n_r, n_c), np.inf)
    units = np.floor(np.clip(d, 0.0, CAP_NM) / UNIT_NM).astype(np.int64) + 1
    grid = np.where(sea, units, 0).astype(np.uint8)
    return np.ascontiguousarray(grid[pad_rows:pad_rows + FINE_PER_TILE,
                                     pad_cols:pad_cols + FINE_PER_TILE])


class FineDistance:
    """Level-1 tiles of one coastline, resolved as walks meet them (thread-safe `add`).

    `grids` has room for more tiles than `count` (rows past it are unused): a new tile is
    written to a free row and the slot map replaced after it, so a walk reading the old pair
    meanwhile stays consistent and adding a few tiles does not copy the thousands built before.
    `save` writes only the tiles built since the last save, to a part file next to `path`;
    loading reads `path` and its parts and merges them into `path` once there are
    `MAX_PARTS` (the whole set is hundreds of MB: rewriting it after each plan cost ~1 s)."""

    def __init__(self, land_near: LandNear, contains: Contains, path: Path | None = None
                 ) -> None:
        self._land_near, self._contains = land_near, contains
        self.slots = np.full((TILE_ROWS, TILE_COLS), -1, dtype=np.int32)
        self.grids = np.zeros((0, FINE_PER_TILE, FINE_PER_TILE), dtype=np.uint8)
        self._keys = np.zeros(0, dtype=np.int64)  # tile key of each used row
        self.count = 0  # rows of `grids` in use
        self._lock = threading.Lock()
        self.path = path
        self._saved = 0
        self.build_s = 0.0  # wall time spent building tiles in this process (`add`)
        self.built = 0  # tiles built in this process
        if path is not None:
            self._load(path)

    def _parts(self) -> list[Path]:
        """The part files of `path` (tiles saved since it was last merged), oldest first."""
        assert self.path is not None
        found = self.path.parent.glob(f"{self.path.stem}{PART_MARK}*.npz")
        return sorted(p for p in found if not p.name.endswith(".tmp.npz"))

    def _load(self, path: Path) -> None:
        """Tiles built earlier, from `path` and its parts (a corrupt or mismatched file is
        ignored; a tile in two files is taken once); many parts are merged into `path`."""
        parts = self._parts()
        keys_of, grids_of = [], []
        for file in ([path] if path.is_file() else []) + parts:
            got = load_npz(file, "keys", "grids")
            if got is None:
                continue
            keys, grids = got[0].astype(np.int64), got[1].astype(np.uint8)
            if grids.shape[1:] != (FINE_PER_TILE, FINE_PER_TILE) or keys.size != grids.shape[0]:
                continue
            if keys.size and (keys.min() < 0 or keys.max() >= TILE_ROWS * TILE_COLS):
                continue
            keys_of.append(keys)
            grids_of.append(grids)
        if not keys_of:
            return
        keys = np.concatenate(keys_of)
        grids = grids_of[0] if len(grids_of) == 1 else np.concatenate(grids_of)
        _, first = np.unique(keys, return_index=True)
        if first.size < keys.size:
            first = np.sort(first)
            keys, grids = keys[first], grids[first]
        self._store(keys, grids)
        self._saved = self.count
        if len(parts) >= MAX_PARTS and save_npz_atomic(path, keys=self._keys[:self.count],
                                                       grids=self.grids[:self.count]):
            for p in parts:
                p.unlink(missing_ok=True)

    def _store(self, keys: np.ndarray, grids: np.ndarray) -> None:
        """Append tiles (keys not yet built) and publish their slots (under the lock, or
        before other threads see the object)."""
        n0, n1 = self.count, self.count + keys.size
        store = self.grids
        if n1 > store.shape[0]:  # zeroed rows cost no memory until written
            store = np.zeros((max(2 * n1, MIN_ROWS), FINE_PER_TILE, FINE_PER_TILE),
                             dtype=np.uint8)
            store[:n0] = self.grids[:n0]
            self._keys = np.concatenate([self._keys[:n0],
                                         np.zeros(store.shape[0] - n0, dtype=np.int64)])
        store[n0:n1] = grids
        self._keys[n0:n1] = keys
        slots = self.slots.copy()
        slots.ravel()[keys] = np.arange(n0, n1, dtype=np.int32)
        self.count = n1
        self.grids, self.slots = store, slots  # grids first: a reader takes slots first

    def snapshot(self) -> FineDistance:
        """A copy of the tiles built so far, kept in memory only (not saved): what a process
        that built exactly these would hold."""
        copy = FineDistance(self._land_near, self._contains, path=None)
        with self._lock:
            copy._store(self._keys[:self.count].copy(), self.grids[:self.count].copy())
        return copy

    def save(self) -> None:
        """Store the tiles built since the last save for later processes (a part file,
        atomic; no-op if none)."""
        with self._lock:
            if self.path is None or self.count == self._saved:
                return
            keys = self._keys[self._saved:self.count].copy()
            grids = self.grids[self._saved:self.count].copy()
            upto = self.count
        part = self.path.with_name(f"{self.path.stem}{PART_MARK}{os.getpid()}-"
                                   f"{time.time_ns()}.npz")
        if save_npz_atomic(part, keys=keys, grids=grids):
            self._saved = upto

    def add(self, keys: np.ndarray) -> int:
        """Build the tiles `keys` (row * TILE_COLS + column) not yet built; how many were new."""
        with self._lock:
            keys = np.unique(np.asarray(keys, dtype=np.int64))
            keys = keys[self.slots.ravel()[keys] < 0]
            if keys.size == 0:
                return 0
            t0 = time.perf_counter()
            new = np.stack([build_tile(int(k) // TILE_COLS, int(k) % TILE_COLS,
                                       self._land_near, self._contains) for k in keys])
            self._store(keys, new)
            self.build_s += time.perf_counter() - t0
            self.built += int(keys.size)
            return int(keys.size)

    def add_box(self, lon_min_deg: float, lon_max_deg: float, lat_min_deg: float,
                lat_max_deg: float, coast_dist: np.ndarray, cell_deg: float, reach_nm: float
                ) -> int:
        """Build every tile of a box (longitudes may run past 180) holding a level-0 cell
        (`coast_dist`, 0.1 NM, cells of `cell_deg`) within `reach_nm` of the coast: the
        tiles a walk can read where level 0 defers to level 1 below `reach_nm`. How many were
        new."""
        from .coast_distance import UNIT_NM as L0_UNIT_NM

        per_tile = round(TILE_DEG / cell_deg)
        near = np.abs(np.asarray(coast_dist)) * L0_UNIT_NM < reach_nm
        tiles = near.reshape(TILE_ROWS, per_tile, TILE_COLS, per_tile).any(axis=(1, 3))
        i0 = max(int((lat_min_deg + 90.0) // TILE_DEG), 0)
        i1 = min(int((lat_max_deg + 90.0) // TILE_DEG), TILE_ROWS - 1)
        cols = np.unique(np.arange(int((lon_min_deg + 180.0) // TILE_DEG),
                                   int((lon_max_deg + 180.0) // TILE_DEG) + 1) % TILE_COLS)
        ii, jj = np.nonzero(tiles[i0:i1 + 1][:, cols])
        return self.add((ii + i0) * TILE_COLS + cols[jj])

    def distance_nm(self, lon_deg: np.ndarray, lat_deg: np.ndarray) -> np.ndarray:
        """Lower bound of the distance to land [NM] at each point; 0 on or touching land, at
        most CAP_NM (builds the tiles the points lie in)."""
        lat = np.asarray(lat_deg, dtype=float)
        lon = (np.asarray(lon_deg, dtype=float) + 180.0) % 360.0 - 180.0
        fine_deg = TILE_DEG / FINE_PER_TILE
        r = np.clip(np.floor((lat + 90.0) / fine_deg).astype(np.int64), 0,
                    TILE_ROWS * FINE_PER_TILE - 1)
        c = np.clip(np.floor((lon + 180.0) / fine_deg).astype(np.int64), 0,
                    TILE_COLS * FINE_PER_TILE - 1)
        self.add((r // FINE_PER_TILE) * TILE_COLS + c // FINE_PER_TILE)
        v = self.grids[self.slots[r // FINE_PER_TILE, c // FINE_PER_TILE],
                       r % FINE_PER_TILE, c % FINE_PER_TILE]
        return np.maximum(v.astype(float) - 1.0, 0.0) * UNIT_NM


_DEFAULT: dict[str, FineDistance] = {}


def tile_builds() -> tuple[int, float]:
    """(tiles, seconds) the process-wide tile sets have built so far: a search tells from
    them how much of its clock went to one-off builds rather than to searching."""
    return (sum(f.built for f in _DEFAULT.values()),
            sum(f.build_s for f in _DEFAULT.values()))


def default_fine_distance() -> FineDistance:
    """The process-wide level-1 tiles of the finest coastline installed (`geo.full_land`),
    saved in the data directory."""
    from .datadir import data_dir
    from .full_land import final_land

    land = final_land()
    found = _DEFAULT.get(land.resolution)
    if found is None:
        path = data_dir() / f"finedistance_v{FINE_DISTANCE_VERSION}_gshhg_{land.resolution}.npz"
        found = _DEFAULT[land.resolution] = FineDistance(land.tiles.land_near, land.contains,
                                                         path)
    return found
