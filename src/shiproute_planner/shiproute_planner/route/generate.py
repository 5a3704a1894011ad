"""Route generation from genes, stage by stage for the whole population (thesis sec. 3.3.2).

Node i + 1 follows from node i by the geodesic direct problem with the course over ground and
speed over ground the ship model gives for stage i's RPM and heading in the weather met at
node i at its time, over the fixed stage duration. The final connection from node n to the
arrival port is sailed with `legs.sail_to` (duration from distance and speed).
"""

from __future__ import annotations

import numpy as np
from shiproute_core.geodesy import direct

from ..geo.landmask import LandMask
from .encoding import split_genes
from .environment import PERF_FIELDS, Environment
from .evaluation import RouteEvaluation, finish
from .legs import perf_arrays, sail_to
from .problem import RouteProblem


def evaluate_genes(
    problem: RouteProblem, env: Environment, land: LandMask | None, x: np.ndarray
) -> RouteEvaluation:
    """Generate and evaluate routes from genes `x` (pop, 2n + 1); loops over stages only."""
    headings, rpm = split_genes(problem, x)
    pop = headings.shape[0]
    n = problem.n_stages
    m = n + 1
    lon = np.empty((pop, m + 1))
    lat = np.empty((pop, m + 1))
    t = np.empty((pop, m + 1))
    lon[:, 0], lat[:, 0], t[:, 0] = problem.dep_lon_deg, problem.dep_lat_deg, problem.depart_s
    legs = {k: np.empty((pop, m)) for k in PERF_FIELDS}
    for i in range(n):
        sea = env.sea_state(lon[:, i], lat[:, i], t[:, i])
        perf = perf_arrays(env.perform(rpm[:, i], headings[:, i], sea), (pop,))
        for k in PERF_FIELDS:
            legs[k][:, i] = perf[k]
        dist = np.maximum(perf["sog_m_s"], 0.0) * problem.stage_s
        lon[:, i + 1], lat[:, i + 1] = direct(lon[:, i], lat[:, i], perf["cog_deg"], dist)
        t[:, i + 1] = t[:, i] + problem.stage_s
    arr_lon = np.full(pop, problem.arr_lon_deg)
    arr_lat = np.full(pop, problem.arr_lat_deg)
    perf, heading_n, dist_n, dur_n = sail_to(
        env, lon[:, n], lat[:, n], t[:, n], arr_lon, arr_lat, rpm[:, n]
    )
    for k in PERF_FIELDS:
        legs[k][:, n] = perf[k]
    lon[:, m], lat[:, m] = problem.arr_lon_deg, problem.arr_lat_deg
    t[:, m] = t[:, n] + dur_n
    all_heading = np.concatenate([headings, heading_n[:, None]], axis=1)
    duration = np.full((pop, m), problem.stage_s)
    duration[:, n] = dur_n
    distance = np.empty((pop, m))
    distance[:, :n] = np.maximum(legs["sog_m_s"][:, :n], 0.0) * problem.stage_s
    distance[:, n] = dist_n
    legs["heading_deg"] = all_heading
    legs["rpm"] = rpm
    legs["distance_m"] = distance
    legs["duration_s"] = duration
    legs["fuel_t"] = legs["fuel_t_per_h"] * duration / 3600.0
    # the thesis bounds the heading-change genes only; the turn onto the final connection is
    # determined by the route, not a design variable (eq. 11), so it is not constrained
    legs["turn_deg"] = np.zeros((pop, m))
    return finish(problem, land, lon, lat, t, legs)
