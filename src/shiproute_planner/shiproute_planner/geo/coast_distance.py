"""Signed lower bound of the distance to the coastline per land-raster cell (level 0).

For a sea cell: the arc [NM, 1 NM = 1 arcminute of the sphere] from any point of the cell to
the nearest land; for an inland cell the arc to the nearest sea, negative; 0 in coastal cells.
The nearest land seen from the sea (and the nearest sea seen from land) lies on the coastline.
The raster (`geo.raster`) marks every cell holding an edge sample (samples <= half a cell
apart) and its eight neighbours coastal, so every coastline point lies at least half a cell
inside the coastal band: the distance between cell centres to the nearest coastal cell, minus
a cell diagonal (any point to any point of the two cells), plus half a cell bounds it from
below. Distances come from scipy's Euclidean distance transform per latitude band, longitude
spacing shrunk by the cosine of the band's most poleward latitude plus the reach (the cap):
on the sphere ds^2 >= dphi^2 + c^2 dlambda^2 wherever cos(lat) >= c, and a path shorter than
the reach stays inside the padded band. Stored as int16 tenths of a NM, floored, capped.
"""

from __future__ import annotations

import math

import numpy as np

from .raster import COAST, LAND

COAST_DISTANCE_VERSION = 2  # in the cache file name: bump when the bound changes
NM_PER_DEG = 60.0  # arc on the sphere: 1 NM per arcminute
UNIT_NM = 0.1  # stored value * UNIT_NM = distance [NM]
# the largest distance stored (and the band padding): farther jumps are the coarse clear
# distances' (`route.fast_eval.coarse_land`); a short reach keeps the longitude shrink tight
CAP_NM = 60.0
BAND_DEG = 2.0  # latitude band per distance transform
MIN_SHRINK = 0.01  # longitude shrink floor at the poles (a smaller bound, still a bound)


def coast_distance(raster: np.ndarray, cell_deg: float, cap_nm: float = CAP_NM,
                   band_deg: float = BAND_DEG) -> np.ndarray:
    """int16 (n_lat, n_lon) signed lower bound of the distance to the coast [UNIT_NM] of each
    cell of a global land raster (row 0 at 90 S, column 0 at 180 W; sea > 0, land < 0)."""
    from scipy.ndimage import distance_transform_edt

    r = np.asarray(raster)
    n_lat, n_lon = r.shape
    cell_nm = cell_deg * NM_PER_DEG
    pad_rows = math.ceil(cap_nm / cell_nm) + 1
    lat_edges = -90.0 + np.arange(n_lat + 1) * cell_deg
    out = np.empty((n_lat, n_lon), dtype=np.int16)
    band_rows = max(1, round(band_deg / cell_deg))
    for a in range(0, n_lat, band_rows):
        b = min(a + band_rows, n_lat)
        poleward = max(abs(lat_edges[a]), abs(lat_edges[b]))
        reach_deg = cap_nm / NM_PER_DEG + cell_deg
        shrink = max(math.cos(math.radians(min(poleward + reach_deg, 90.0))), MIN_SHRINK)
        pad_cols = min(math.ceil(cap_nm / (cell_nm * shrink)) + 1, n_lon)
        ra, rb = max(a - pad_rows, 0), min(b + pad_rows, n_lat)
        block = r[ra:rb]
        tiled = np.concatenate([block[:, n_lon - pad_cols:], block, block[:, :pad_cols]], axis=1)
        coast = tiled == COAST
        if coast.any():
            d = distance_transform_edt(~coast, sampling=(cell_nm, cell_nm * shrink))
            d = d[a - ra:b - ra, pad_cols:pad_cols + n_lon]
        else:
            d = np.full((b - a, n_lon), np.inf)
        # any point of this cell to any point of the coastal cell: minus one cell diagonal;
        # the coastline lies half a cell inside the band of coastal cells
        d = d - math.hypot(cell_nm, cell_nm * shrink) + 0.5 * cell_nm * shrink
        units = np.floor(np.clip(d, 0.0, cap_nm) / UNIT_NM).astype(np.int16)
        out[a:b] = np.where(r[a:b] == LAND, -units, units)
        out[a:b][r[a:b] == COAST] = 0
    return out
