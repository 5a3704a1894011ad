"""Dense samples of a whole track in one geodesic pass, with the leg each sample belongs to
(the final land check and the route check test every leg's samples in one land test)."""

from __future__ import annotations

import numpy as np
from shiproute_core.geodesy import densify_track


def track_samples(lon: np.ndarray, lat: np.ndarray, dist_m: np.ndarray, step_m: float
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Samples every `step_m` along a track of legs `dist_m` [m] long: (lon, lat, index of
    each leg's start node, points per leg, distance along the track [m]). Leg k owns samples
    first[k] (its start node, exactly) .. first[k] + count[k]; a leg's longitudes continue
    its start node's frame."""
    plon, plat = densify_track(lon, lat, step_m)
    n = np.maximum(1, np.ceil(dist_m / step_m).astype(np.int64))
    first = np.concatenate([[0], np.cumsum(n)[:-1]])
    owner = np.concatenate([[0], np.repeat(np.arange(dist_m.size), n)])
    step = np.concatenate([[0], np.arange(owner.size - 1) - first[owner[1:]] + 1])
    along = np.concatenate([[0.0], np.cumsum(dist_m)])[owner] + dist_m[owner] * step / n[owner]
    plon = lon[owner] + (np.asarray(plon, dtype=float) - lon[owner] + 180.0) % 360.0 - 180.0
    plat = np.array(plat, dtype=float)
    plon[first], plat[first] = lon[:-1], lat[:-1]
    return plon, plat, first, n, along
