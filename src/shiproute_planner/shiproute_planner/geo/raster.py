"""Build the land raster: each cell sea (0), land (1) or coastal (2, holds coastline).

Coastal cells are those a densified polygon edge passes through, dilated by one cell so that
the small bulge of a geodesic between samples stays inside them. Every other cell lies in a
connected patch without coastline, so one exact point test per patch (its first cell's
centre) classifies the whole patch as land or sea.
"""

from __future__ import annotations

import numpy as np
from scipy import ndimage

from .gshhg import LandPolygons
from .landexact import ExactLand

SEA, LAND, COAST = 0, 1, 2


def _edge_samples(polygons: LandPolygons, step_deg: float) -> tuple[np.ndarray, np.ndarray]:
    """Points along every polygon edge, no further apart than `step_deg`."""
    v = polygons.lon_lat
    last = np.zeros(v.shape[0], dtype=bool)
    last[polygons.start + polygons.count - 1] = True
    p0 = v[:-1][~last[:-1]]
    p1 = v[1:][~last[:-1]]
    length = np.hypot(*(p1 - p0).T)
    n = np.maximum(1, np.ceil(length / step_deg).astype(np.int64))
    edge = np.repeat(np.arange(p0.shape[0]), n)
    first = np.concatenate([[0], np.cumsum(n)[:-1]])
    frac = (np.arange(edge.size) - first[edge]) / n[edge]
    pts = p0[edge] + (p1 - p0)[edge] * frac[:, None]
    return pts[:, 0], pts[:, 1]


def patch_representatives(free: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Connected patches of the True cells of `free` (labels, 0 outside) and the flat index of
    each patch's first cell in row-major order (one exact test classifies a whole patch)."""
    labels, n_labels = ndimage.label(free)
    flat = labels.ravel()
    cells = np.flatnonzero(flat)
    first = np.full(n_labels + 1, -1, dtype=np.int64)
    first[flat[cells[::-1]]] = cells[::-1]
    return labels, first[1:]


def build_land_raster(polygons: LandPolygons, exact: ExactLand, cell_deg: float) -> np.ndarray:
    """uint8 raster (n_lat, n_lon) over lat -90..90, lon -180..180, row 0 at the south."""
    n_lat = round(180.0 / cell_deg)
    n_lon = round(360.0 / cell_deg)
    lon, lat = _edge_samples(polygons, cell_deg * 0.5)
    i = np.clip(((lat + 90.0) / cell_deg).astype(np.int64), 0, n_lat - 1)
    j = np.clip(((lon + 180.0) / cell_deg).astype(np.int64), 0, n_lon - 1)
    coast = np.zeros((n_lat, n_lon), dtype=bool)
    coast[i, j] = True
    coast = ndimage.binary_dilation(coast, structure=np.ones((3, 3), dtype=bool))
    labels, rep = patch_representatives(~coast)
    rep_lat = (rep // n_lon + 0.5) * cell_deg - 90.0
    rep_lon = (rep % n_lon + 0.5) * cell_deg - 180.0
    is_land = np.concatenate([[False], exact.contains(rep_lon, rep_lat)])
    raster = np.where(is_land[labels], LAND, SEA).astype(np.uint8)
    raster[coast] = COAST
    return raster
