"""Sail given waypoint tracks with per-leg RPM, time-marching with the same leg physics.

For baselines (great circle, sea lanes, isochrone, A*, 3DDP) and for re-evaluating an old plan
in a new forecast: each leg is steered so its course over ground points at the next waypoint,
in the weather met at the leg's start, and lasts distance / speed over ground.
"""

from __future__ import annotations

import numpy as np
from shiproute_core.geodesy import unwrap_near

from ..geo.landmask import LandMask
from .environment import PERF_FIELDS, Environment
from .evaluation import RouteEvaluation, finish
from .legs import sail_to
from .problem import RouteProblem


def sail_tracks(
    problem: RouteProblem,
    env: Environment,
    land: LandMask | None,
    track_lon_deg: np.ndarray,
    track_lat_deg: np.ndarray,
    rpm: np.ndarray,
    depart_s: np.ndarray | float | None = None,
) -> RouteEvaluation:
    """Evaluate tracks (pop, m + 1) sailed at `rpm` (pop, m) or (m,) or scalar.

    Pad shorter tracks by repeating their last point (zero-length legs are ignored). Longitudes
    may be in any frame; they are made continuous along each track.
    """
    lon = np.atleast_2d(np.asarray(track_lon_deg, dtype=float))
    lat = np.atleast_2d(np.asarray(track_lat_deg, dtype=float))
    pop, m1 = lon.shape
    m = m1 - 1
    lon = np.unwrap(lon, period=360.0, axis=1)
    lon = lon - np.round((lon[:, :1] - problem.dep_lon_deg) / 360.0) * 360.0
    rpm = np.broadcast_to(np.asarray(rpm, dtype=float), (pop, m)).copy()
    t = np.empty((pop, m1))
    t[:, 0] = problem.depart_s if depart_s is None else depart_s
    legs = {k: np.zeros((pop, m)) for k in PERF_FIELDS}
    heading = np.zeros((pop, m))
    distance = np.zeros((pop, m))
    duration = np.zeros((pop, m))
    for k in range(m):
        perf, h, d, dur = sail_to(env, lon[:, k], lat[:, k], t[:, k],
                                  unwrap_near(lon[:, k + 1], lon[:, k]), lat[:, k + 1], rpm[:, k])
        for f in PERF_FIELDS:
            legs[f][:, k] = perf[f]
        heading[:, k], distance[:, k], duration[:, k] = h, d, dur
        t[:, k + 1] = t[:, k] + dur
    legs["heading_deg"] = heading
    legs["rpm"] = rpm
    legs["distance_m"] = distance
    legs["duration_s"] = duration
    legs["fuel_t"] = legs["fuel_t_per_h"] * duration / 3600.0
    legs["turn_deg"] = np.zeros((pop, m))  # given tracks: turns are not design variables
    return finish(problem, land, lon, lat, t, legs)
