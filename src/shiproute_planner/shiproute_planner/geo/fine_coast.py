"""Exact land verdicts on a fine grid inside the raster's coastal cells, filled lazily.

The GA's compiled land scan decides samples in sea and land cells from the 0.05-deg raster;
in coastal cells it looks up the sample's fine cell (`cell_deg / factor`, ~1 km by default),
which is land when the exact GSHHG test puts its centre or a neighbouring fine cell's centre
on land: a margin of about one fine cell, so routes the GA accepts clear the dense check of
the final plan (points every 500 m). Coastal cells are resolved on first use, all their fine
cells in one vectorised polygon test, and kept for the life of the land mask, so a GA whose
routes sweep the same coasts generation after generation pays each cell once.
"""

from __future__ import annotations

import threading
from pathlib import Path

import numpy as np

from .datadir import load_npz, save_npz_atomic
from .raster import COAST
from .region_box import region_box


class FineCoast:
    """Lazily resolved fine land grid of the coastal cells of a `LandMask` raster."""

    def __init__(self, raster: np.ndarray, cell_deg: float, contains, factor: int = 5,
                 path: Path | None = None) -> None:
        self.raster = raster
        self.cell_deg = float(cell_deg)
        self.factor = int(factor)
        self._contains = contains  # exact point-in-land test: (lon, lat) arrays -> bool array
        self.n_lon = int(raster.shape[1])
        # resolved coastal cells: sorted keys (i * n_lon + j) and their fine grids, row-aligned
        # (sorted arrays: the compiled scan finds a cell by binary search)
        self.keys = np.zeros(0, dtype=np.int64)
        self.fine = np.zeros((0, self.factor, self.factor), dtype=np.bool_)
        self._lock = threading.Lock()
        self.path = path  # cells resolved by earlier processes, extended by `save`
        self._saved = 0
        if path is not None and path.is_file():
            self._load(path)

    def _load(self, path: Path) -> None:
        """Cells resolved earlier (a corrupt or mismatched file is ignored and rebuilt)."""
        got = load_npz(path, "keys", "fine")
        if got is None:
            return
        keys, fine = got[0].astype(np.int64), got[1].astype(np.bool_)
        if fine.shape[1:] == (self.factor, self.factor) and keys.size == fine.shape[0] and (
                np.all(np.diff(keys) > 0)):
            self.keys, self.fine, self._saved = keys, fine, keys.size

    def save(self) -> None:
        """Store the resolved cells for later processes (atomic replace; no-op if unchanged)."""
        with self._lock:
            if self.path is None or self.keys.size == self._saved:
                return
            keys, fine = self.keys, self.fine
        if save_npz_atomic(self.path, keys=keys, fine=fine):
            self._saved = keys.size

    def add(self, keys: np.ndarray) -> int:
        """Resolve the coastal cells `keys` not yet known; returns how many were new."""
        with self._lock:
            keys = np.unique(np.asarray(keys, dtype=np.int64))
            pos = np.minimum(np.searchsorted(self.keys, keys), max(self.keys.size - 1, 0))
            if self.keys.size:
                keys = keys[self.keys[pos] != keys]
            if keys.size == 0:
                return 0
            i, j = keys // self.n_lon, keys % self.n_lon
            if not np.all(np.asarray(self.raster)[i, j] == COAST):
                raise ValueError("FineCoast.add: keys must name coastal raster cells")
            f = self.factor
            sub = (np.arange(-1, f + 1) + 0.5) / f  # the cell's fine cells and a ring around
            lat = -90.0 + (i[:, None, None] + sub[None, :, None]) * self.cell_deg
            lon = -180.0 + (j[:, None, None] + sub[None, None, :]) * self.cell_deg
            lat, lon = np.broadcast_arrays(lat, lon)
            land = np.asarray(self._contains(lon.ravel(), lat.ravel()), dtype=np.bool_)
            land = land.reshape(-1, f + 2, f + 2)
            grown = np.zeros((keys.size, f, f), dtype=np.bool_)
            for di in range(3):  # land within one fine cell (8-neighbourhood)
                for dj in range(3):
                    grown |= land[:, di:di + f, dj:dj + f]
            all_keys = np.concatenate([self.keys, keys])
            order = np.argsort(all_keys, kind="stable")
            self.keys, self.fine = all_keys[order], np.concatenate([self.fine, grown])[order]
            return int(keys.size)

    def resolve_box(self, lon_min_deg: float, lon_max_deg: float, lat_min_deg: float,
                    lat_max_deg: float) -> int:
        """Resolve every coastal cell in a box (longitudes may run past 180); returns how
        many were new. ~20,000 cells/s, once per machine when `save`d."""
        inv = 1.0 / self.cell_deg
        raster = np.asarray(self.raster)
        i0 = max(int((lat_min_deg + 90.0) * inv), 0)
        i1 = min(int((lat_max_deg + 90.0) * inv) + 1, raster.shape[0])
        cols = (np.arange(int(lon_min_deg * inv), int(lon_max_deg * inv) + 1)
                + int(180.0 * inv)) % self.n_lon
        ii, jj = np.nonzero(raster[i0:i1][:, np.unique(cols)] == COAST)
        return self.add((ii + i0) * self.n_lon + np.unique(cols)[jj])

    def resolve_voyage(self, a: tuple[float, float], b: tuple[float, float],
                       margins_deg: tuple[float, float, float, float]) -> int:
        """Resolve the coastal cells of a voyage's region (`region_box`: the box between
        points `a` and `b` ((lon, lat) [deg]) the shorter way round, widened by (west, east,
        south, north) margins [deg]). Returns how many cells were new."""
        return self.resolve_box(*region_box(a, b, margins_deg))

    def contains(self, lon_deg: np.ndarray, lat_deg: np.ndarray) -> np.ndarray:
        """Verdict of the fine cell holding each point (coastal cells only; resolves them)."""
        inv = 1.0 / self.cell_deg
        lat = np.asarray(lat_deg, dtype=float)
        lon = (np.asarray(lon_deg, dtype=float) + 180.0) % 360.0
        i = np.floor((lat + 90.0) * inv).astype(np.int64)
        j = np.floor(lon * inv).astype(np.int64)
        self.add(i * self.n_lon + j)
        f = self.factor
        fi = np.minimum(((lat + 90.0) * inv - i) * f, f - 1).astype(np.int64)
        fj = np.minimum((lon * inv - j) * f, f - 1).astype(np.int64)
        slot = np.searchsorted(self.keys, i * self.n_lon + j)
        return self.fine[slot, fi, fj]
