"""The first round of track repairs runs even when the seeding share is spent
(`track_repairs`): a stale re-plan without repairs rarely ends feasible, and its re-timed
tracks are cheap. A route sailed 10 % too slowly for its RTA in calm water (open North
Pacific, great circle) is late over its whole length; with the share spent from the start
the repairs are the re-timed tracks alone, and one of them arrives on time (the engine has
the RPM for it)."""

from __future__ import annotations

import numpy as np
from shiproute_planner.plan_setup import route_limits
from shiproute_planner.route.generate import evaluate_genes
from shiproute_planner.route.problem import RouteProblem
from shiproute_planner.route.seeding import TrackSeed, great_circle_track, track_to_genes
from shiproute_planner.track_repairs import track_repairs

T0_S = 1_772_560_800.0  # 2026-03-03T18:00Z
STAGES = 8


def _problem(lim, window_s: float) -> RouteProblem:
    return RouteProblem(160.0, 40.0, 200.0, 40.0, T0_S, T0_S + window_s, lim,
                        stage_s=12 * 3600.0, n_stages=STAGES)


def test_first_repair_round_runs_with_the_seeding_share_spent(calm_env):
    env, spec = calm_env
    lim = route_limits(spec)
    rpm = lim.rpm_min + 0.4 * (lim.rpm_max - lim.rpm_min)
    free = _problem(lim, 30 * 86400.0)  # no RTA in reach: how long the route takes
    lon, lat = great_circle_track(free, 40)
    seed = TrackSeed("previous_plan", lon, lat, np.full(lon.size - 1, rpm))
    took_s = float(evaluate_genes(free, env, None, track_to_genes(free, env, [seed])).eta_s[0]
                   - T0_S)
    problem = _problem(lim, took_s / 1.1)  # the RTA asks for 10 % more speed
    x = track_to_genes(problem, env, [seed])
    ev = evaluate_genes(problem, env, None, x)
    assert ev.violation[0] > 0.0  # late
    genes, names, feasible = track_repairs(
        problem, env, None, None, ev, 0, lambda g: evaluate_genes(problem, env, None, g),
        spent=lambda: True)
    assert len(names) > 0 and set(names) == {"previous_plan_retimed"}
    assert feasible
    repaired = evaluate_genes(problem, env, None, genes)
    assert (repaired.eta_s <= problem.rta_s).any()
