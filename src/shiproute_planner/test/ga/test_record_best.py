"""The GA loop's records of its best (`seed_ga.record_best`) and the exact final choice's
fallback on them: a best unchanged since the last record is kept once, and when no final
candidate is feasible to the exact evaluator, the recorded best it finds feasible wins."""

from __future__ import annotations

import numpy as np
from shiproute_planner.experiments.bench.planner import ga_like_population
from shiproute_planner.plan_setup import make_environment, route_limits, to_posix_s
from shiproute_planner.route.generate import evaluate_genes
from shiproute_planner.route.problem import RouteProblem

from shiproute_planner import seed_ga


def genes_and_problem() -> tuple[RouteProblem, object, np.ndarray]:
    """Three routes of a 5-day calm leg: x0 at 40 RPM and x2 at 36 RPM on time, x1 late."""
    env, spec = make_environment("container_4600teu", None)
    d = to_posix_s("2026-03-03T18:00Z")
    p = RouteProblem(-30.0, 40.0, -10.0, 45.0, d, d + 5 * 86400.0, route_limits(spec))
    x = ga_like_population(p, 3, np.random.default_rng(2))
    n = p.n_stages
    # 900 NM in nine 12-h stages and a final connection: on time at 36-40 RPM (faster
    # overshoots and turns back, later); at 28 RPM over a day late
    x[0, n:], x[2, n:] = 40.0, 36.0
    x[1, n:] = 28.0
    return p, env, x


def test_an_unchanged_best_is_recorded_once() -> None:
    _, _, x = genes_and_problem()
    sequence = [x[0], x[0], x[1], x[1], x[0], x[2], x[2]]  # the GA's best at each check
    recorded: list[np.ndarray] = []
    for best in sequence:
        seed_ga.record_best(best, recorded)
    assert [tuple(c) for c in recorded] == [tuple(x[0]), tuple(x[1]), tuple(x[0]), tuple(x[2])]
    recorded[0][0] += 1.0  # copies: the GA's own arrays are not aliased
    assert recorded[0][0] != x[0][0]


def test_final_choice_falls_back_on_recorded_bests() -> None:
    p, env, x = genes_and_problem()
    verdicts = evaluate_genes(p, env, None, x).feasible
    assert verdicts[0] and not verdicts[1] and verdicts[2]
    # the final candidates (two late copies of x1, and their RPM-scaled copies) fail; the
    # recorded bests behind them are judged in the same exact call's fallback: the slower
    # of the two on-time routes burns less (same route shape, 36 vs 40 RPM)
    pool = np.stack([x[1], x[1], x[0], x[2]])
    chosen, ev = seed_ga.exact_choice(p, env, None, pool, top=2)
    assert ev.feasible[0]
    np.testing.assert_array_equal(chosen, x[2])
    assert ev.objective[0] < evaluate_genes(p, env, None, x[:1]).objective[0]
