"""Exact point-in-land tests against GSHHG polygons (shapely, prepared, built lazily).

Only polygons whose bounding box holds a query point are turned into shapely geometries, so
a planner that stays near two coasts touches a few hundred polygons, not all 33,000.
"""

from __future__ import annotations

import numpy as np
import shapely

from .gshhg import LandPolygons


class ExactLand:
    """Point-in-polygon tests of (lon, lat) points against one set of land polygons."""

    def __init__(self, polygons: LandPolygons) -> None:
        self.polygons = polygons
        b = polygons.bounds
        self._tree = shapely.STRtree(shapely.box(b[:, 0], b[:, 1], b[:, 2], b[:, 3]))
        self._geoms = np.empty(len(polygons), dtype=object)

    def _geometry(self, ids: np.ndarray) -> np.ndarray:
        """Prepared shapely polygons for polygon indices `ids` (built on first use)."""
        missing = np.unique(ids[self._geoms[ids] == None])  # noqa: E711 - object array test
        if missing.size:
            rings = [shapely.Polygon(self.polygons.ring(int(i))) for i in missing]
            new = np.array(rings, dtype=object)
            new = np.where(shapely.is_valid(new), new, shapely.make_valid(new))
            shapely.prepare(new)
            self._geoms[missing] = new
        return self._geoms[ids]

    def contains(self, lon_deg: np.ndarray, lat_deg: np.ndarray) -> np.ndarray:
        """True where the point lies on land; longitudes in any 360-degree frame."""
        lon = (np.asarray(lon_deg, dtype=float).ravel() + 180.0) % 360.0 - 180.0
        lat = np.asarray(lat_deg, dtype=float).ravel()
        out = np.zeros(lon.size, dtype=bool)
        if lon.size == 0:
            return out.reshape(np.shape(lon_deg))
        pts = shapely.points(lon, lat)
        pt_idx, poly_idx = self._tree.query(pts, predicate="intersects")
        if pt_idx.size:
            geoms = self._geometry(poly_idx)
            hit = shapely.intersects_xy(geoms, lon[pt_idx], lat[pt_idx])
            out[pt_idx[hit]] = True
        return out.reshape(np.shape(lon_deg))

    def clipped(self, lon_min: float, lat_min: float, lon_max: float, lat_max: float):
        """Land inside a lon/lat box (-180..180, not across the antimeridian) as one
        geometry, for distance-to-land tests (clearance)."""
        ids = self._tree.query(shapely.box(lon_min, lat_min, lon_max, lat_max))
        if ids.size == 0:
            return shapely.Polygon()
        geoms = self._geometry(np.asarray(ids))
        parts = shapely.clip_by_rect(geoms, lon_min, lat_min, lon_max, lat_max)
        return shapely.union_all(parts[~shapely.is_empty(parts)])
