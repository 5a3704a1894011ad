"""The lowest constant RPM at which a fixed track meets the RTA (planner's `sail_tracks`).

Path-only methods hold one RPM for the whole voyage; the fair constant RPM is the lowest one
that still arrives by the RTA on the path found. The track is sailed at many RPMs in one
population call, then once more on a finer bracket.
"""

from __future__ import annotations

import numpy as np

from ..geo.landmask import LandMask
from ..route.environment import Environment
from ..route.evaluation import RouteEvaluation
from ..route.problem import RouteProblem
from ..route.sail import sail_tracks


def constant_rpm_for_rta(
    problem: RouteProblem,
    env: Environment,
    land: LandMask | None,
    lon_deg: np.ndarray,
    lat_deg: np.ndarray,
    coarse: int = 33,
    fine: int = 33,
) -> tuple[float, RouteEvaluation, int]:
    """(rpm, single-route evaluation at that rpm, route evaluations used).

    If even the maximum RPM is late, the maximum RPM is returned (best effort, flagged late
    by the evaluation).
    """
    lim = problem.limits
    evals = 0

    def sail(rpms: np.ndarray) -> RouteEvaluation:
        nonlocal evals
        evals += rpms.size
        k = rpms.size
        return sail_tracks(problem, env, land, np.tile(lon_deg, (k, 1)), np.tile(lat_deg, (k, 1)),
                           np.repeat(rpms[:, None], lon_deg.size - 1, axis=1))

    grid = np.linspace(lim.rpm_min, lim.rpm_max, coarse)
    ev = sail(grid)
    on_time = np.flatnonzero(ev.eta_s <= problem.rta_s)
    if on_time.size == 0:
        return float(grid[-1]), ev.take(coarse - 1), evals
    i = int(on_time[0])
    if i == 0:
        return float(grid[0]), ev.take(0), evals
    fine_grid = np.linspace(grid[i - 1], grid[i], fine)
    ev2 = sail(fine_grid)
    ok = np.flatnonzero(ev2.eta_s <= problem.rta_s)
    j = int(ok[0]) if ok.size else fine - 1
    return float(fine_grid[j]), ev2.take(j), evals
