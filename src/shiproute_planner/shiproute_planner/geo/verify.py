"""Independent land check of a finished track: dense geodesic samples, exact polygon test.

Finer than the planner's check (geodesic points every `step_m` instead of straight-line
samples every 0.05 deg, every sample tested against the polygons rather than the raster).
"""

from __future__ import annotations

import numpy as np

from .geodesy import densify_track, inverse
from .gshhg import load_land_polygons
from .landexact import ExactLand


def land_crossings(lon_deg: np.ndarray, lat_deg: np.ndarray, resolution: str = "i",
                   step_m: float = 500.0, port_clearance_m: float = 3000.0,
                   exact: ExactLand | None = None) -> list[int]:
    """Indices of legs of a track with any sample on land (ports' clearance excluded).

    `exact` reuses an already built polygon test (e.g. `LandMask.exact`) of `resolution`."""
    lon = np.unwrap(np.asarray(lon_deg, dtype=float), period=360.0)
    lat = np.asarray(lat_deg, dtype=float)
    exact = exact or ExactLand(load_land_polygons(resolution))
    _, dist = inverse(lon[:-1], lat[:-1], lon[1:], lat[1:])
    total = np.concatenate([[0.0], np.cumsum(dist)])
    bad = []
    for k in range(lon.size - 1):
        if dist[k] <= 0:
            continue
        plon, plat = densify_track(lon[k:k + 2], lat[k:k + 2], step_m)
        along = total[k] + np.linspace(0.0, dist[k], plon.size)
        keep = (along > port_clearance_m) & (along < total[-1] - port_clearance_m)
        if keep.any() and exact.contains(plon[keep], plat[keep]).any():
            bad.append(k)
    return bad
