"""Local refinement of an RPM schedule on a fixed path (SLSQP on per-block RPM, exact evaluator).

The time-binned DP of `speed_schedule` finds the shape of a good schedule but loses a little
to its bins when the RTA binds. This step minimises the evaluator's own fuel with the RTA as an
inequality constraint, over one RPM per block of consecutive legs (about one GA stage of
sailing each). Gradients are forward differences, all in one population call of
`route.sail.sail_tracks`, so each iteration costs a single evaluator pass.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import minimize

from ..geo.landmask import LandMask
from ..route.environment import Environment
from ..route.evaluation import RouteEvaluation
from ..route.problem import RouteProblem
from ..route.sail import sail_tracks

FD_STEP_RPM = 0.05
RTA_SAFETY_H = 0.02  # aim this far inside the RTA so rounding never makes the plan late


def leg_blocks(duration_s: np.ndarray, block_s: float) -> np.ndarray:
    """Block index of every leg: consecutive legs grouped into about `block_s` of sailing."""
    start = np.r_[0.0, np.cumsum(duration_s)[:-1]]
    raw = np.floor(start / block_s).astype(np.int64)
    return np.unique(raw, return_inverse=True)[1].astype(np.int64)  # no empty blocks


def refine_schedule(
    problem: RouteProblem,
    env: Environment,
    land: LandMask | None,
    lon_deg: np.ndarray,
    lat_deg: np.ndarray,
    rpm_start: np.ndarray,
    block_s: float,
    max_iter: int = 40,
) -> tuple[np.ndarray, RouteEvaluation, int]:
    """(per-leg RPM, its evaluation, route evaluations used) after SLSQP from `rpm_start`."""
    lim = problem.limits
    first = sail_tracks(problem, env, None, lon_deg[None], lat_deg[None], rpm_start[None])
    block = leg_blocks(first.legs["duration_s"][0], block_s)
    n_b = int(block.max()) + 1
    x0 = np.array([np.mean(rpm_start[block == b]) for b in range(n_b)])
    evals = 1
    cache: dict[bytes, tuple[float, float, np.ndarray, np.ndarray]] = {}

    def batch(x: np.ndarray) -> tuple[float, float, np.ndarray, np.ndarray]:
        nonlocal evals
        key = x.tobytes()
        if key not in cache:
            xs = np.vstack([x, x + FD_STEP_RPM * np.eye(n_b)])
            ev = sail_tracks(problem, env, None, np.broadcast_to(lon_deg, (n_b + 1, lon_deg.size)),
                             np.broadcast_to(lat_deg, (n_b + 1, lat_deg.size)), xs[:, block])
            evals += n_b + 1
            slack_h = (problem.rta_s - ev.eta_s) / 3600.0 - RTA_SAFETY_H
            cache.clear()
            cache[key] = (float(ev.fuel_t[0]), float(slack_h[0]),
                          (ev.fuel_t[1:] - ev.fuel_t[0]) / FD_STEP_RPM,
                          (slack_h[1:] - slack_h[0]) / FD_STEP_RPM)
        return cache[key]

    res = minimize(
        lambda x: batch(x)[0], x0, jac=lambda x: batch(x)[2], method="SLSQP",
        bounds=[(lim.rpm_min, lim.rpm_max)] * n_b,
        constraints=[{"type": "ineq", "fun": lambda x: batch(x)[1],
                      "jac": lambda x: batch(x)[3]}],
        options={"maxiter": max_iter, "ftol": 1e-6},
    )
    x = np.clip(res.x, lim.rpm_min, lim.rpm_max)
    rpm = x[block]
    final = sail_tracks(problem, env, land, lon_deg[None], lat_deg[None], rpm[None])
    return rpm, final, evals + 1
