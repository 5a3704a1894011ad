"""Sail one given track with per-leg RPM, all legs at once: the leg start times are found as
the fixed point of "time at a node = departure + the durations of the legs before it, each
sailed in the weather met at its own start" (Jacobi iterations over every leg).

The answer is the time-marching one of `sail.sail_tracks` (the legs' start times agree to
within `TIME_TOLERANCE_S`), at a few vectorised passes instead of one Python step per leg:
a re-plan sails a kept plan's remainder, strait passages and approaches of 20-60 legs each.
The march itself is the fallback when the iterations do not settle.
"""

from __future__ import annotations

import numpy as np

from ..geo.landmask import LandMask
from .environment import PERF_FIELDS, Environment
from .evaluation import RouteEvaluation, finish
from .legs import sail_to
from .problem import RouteProblem
from .sail import sail_tracks

TIME_TOLERANCE_S = 1.0  # node times settled when no node moves more than this
MAX_PASSES = 12  # one pass fixes at least one more node exactly: a long track may need more


def sail_track(problem: RouteProblem, env: Environment, land: LandMask | None,
               lon_deg: np.ndarray, lat_deg: np.ndarray, rpm: np.ndarray,
               time_guess_s: np.ndarray | None = None) -> RouteEvaluation:
    """One track (m + 1 nodes) sailed at `rpm` (m,) or scalar from `problem.depart_s`, as
    `sail_tracks` evaluates it; `time_guess_s` (m + 1,) starts the iterations (e.g. the
    planned times of a kept plan), else the first pass sails every leg at the departure."""
    lon = np.unwrap(np.asarray(lon_deg, dtype=float), period=360.0)
    lon = lon - np.round((lon[0] - problem.dep_lon_deg) / 360.0) * 360.0
    lat = np.asarray(lat_deg, dtype=float)
    m = lon.size - 1
    r = np.broadcast_to(np.asarray(rpm, dtype=float), (m,)).copy()
    t0 = float(problem.depart_s)
    t = (np.full(m + 1, t0) if time_guess_s is None
         else np.asarray(time_guess_s, dtype=float) - float(time_guess_s[0]) + t0)
    for _ in range(MAX_PASSES):
        perf, heading, dist, dur = sail_to(env, lon[:-1], lat[:-1], t[:-1], lon[1:], lat[1:], r)
        t_new = np.concatenate([[t0], t0 + np.cumsum(dur)])
        settled = bool(np.max(np.abs(t_new - t)) <= TIME_TOLERANCE_S)
        t = t_new
        if settled:
            break
    else:  # the weather along the track would not let the times settle: march leg by leg
        return sail_tracks(problem, env, land, lon[None, :], lat[None, :], r[None, :])
    legs = {k: np.asarray(perf[k], dtype=float)[None, :].copy() for k in PERF_FIELDS}
    legs["heading_deg"] = np.asarray(heading, dtype=float)[None, :]
    legs["rpm"] = r[None, :]
    legs["distance_m"] = np.asarray(dist, dtype=float)[None, :]
    legs["duration_s"] = np.asarray(dur, dtype=float)[None, :]
    legs["fuel_t"] = legs["fuel_t_per_h"] * legs["duration_s"] / 3600.0
    legs["turn_deg"] = np.zeros((1, m))  # given tracks: turns are not design variables
    return finish(problem, land, lon[None, :], lat[None, :], t[None, :], legs)
