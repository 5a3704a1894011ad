"""Exact land verdicts on a fine grid inside the raster's coastal cells, filled lazily.

The GA's compiled land scan decides samples in sea and land cells from the 0.05-deg raster;
in coastal cells it looks up the exact GSHHG verdict at the centre of the sample's fine cell
(`cell_deg / factor`, ~1 km by default). Coastal cells are resolved on first use, all their
fine cells in one vectorised polygon test, and kept for the life of the land mask, so a GA
whose routes sweep the same coasts generation after generation pays each cell once.
"""

from __future__ import annotations

import threading

import numpy as np
from numba import types
from numba.typed import Dict

from .raster import COAST


class FineCoast:
    """Lazily resolved fine land grid of the coastal cells of a `LandMask` raster."""

    def __init__(self, raster: np.ndarray, cell_deg: float, contains, factor: int = 5) -> None:
        self.raster = raster
        self.cell_deg = float(cell_deg)
        self.factor = int(factor)
        self._contains = contains  # exact point-in-land test: (lon, lat) arrays -> bool array
        self.n_lon = int(raster.shape[1])
        # coastal cell key (i * n_lon + j) -> slot in `fine`
        self.slots = Dict.empty(key_type=types.int64, value_type=types.int64)
        self.fine = np.zeros((0, self.factor, self.factor), dtype=np.bool_)
        self._lock = threading.Lock()

    def add(self, keys: np.ndarray) -> int:
        """Resolve the coastal cells `keys` not yet known; returns how many were new."""
        with self._lock:
            keys = np.unique(np.asarray(keys, dtype=np.int64))
            keys = np.array([k for k in keys.tolist() if k not in self.slots], dtype=np.int64)
            if keys.size == 0:
                return 0
            i, j = keys // self.n_lon, keys % self.n_lon
            if not np.all(np.asarray(self.raster)[i, j] == COAST):
                raise ValueError("FineCoast.add: keys must name coastal raster cells")
            f = self.factor
            sub = (np.arange(f) + 0.5) / f
            lat = -90.0 + (i[:, None, None] + sub[None, :, None]) * self.cell_deg
            lon = -180.0 + (j[:, None, None] + sub[None, None, :]) * self.cell_deg
            lat, lon = np.broadcast_arrays(lat, lon)
            land = np.asarray(self._contains(lon.ravel(), lat.ravel()), dtype=np.bool_)
            base = self.fine.shape[0]
            self.fine = np.concatenate([self.fine, land.reshape(-1, f, f)])
            for n, k in enumerate(keys.tolist()):
                self.slots[k] = base + n
            return int(keys.size)

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
        slot = np.array([self.slots[k] for k in (i * self.n_lon + j).tolist()], dtype=np.int64)
        return self.fine[slot, fi, fj]
