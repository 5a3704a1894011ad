"""The GA loop's exact confirmations of its best (`seed_ga.confirm_best`): a best already
judged by the exact evaluator is not evaluated again, and the confirmations are those of
evaluating every time."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
from shiproute_planner.experiments.bench.planner import ga_like_population
from shiproute_planner.plan_setup import make_environment, route_limits, to_posix_s
from shiproute_planner.route.generate import evaluate_genes
from shiproute_planner.route.problem import RouteProblem

from shiproute_planner import seed_ga


def test_an_unchanged_best_is_judged_once_with_the_same_verdicts(monkeypatch):
    env, spec = make_environment("container_4600teu", None)
    d = to_posix_s("2026-03-03T18:00Z")
    p = RouteProblem(-30.0, 40.0, -10.0, 45.0, d, d + 5 * 86400.0, route_limits(spec))
    ctx = SimpleNamespace(env=env, land=None)
    x = ga_like_population(p, 3, np.random.default_rng(2))
    n = p.n_stages
    # 900 NM in nine 12-h stages and a final connection: on time at 36-40 RPM (faster
    # overshoots and turns back, later); at 28 RPM over a day late
    x[0, n:], x[2, n:] = 40.0, 36.0
    x[1, n:] = 28.0
    calls: list[int] = []

    def counted(problem, env, land, genes):
        calls.append(len(genes))
        return evaluate_genes(problem, env, land, genes)

    monkeypatch.setattr(seed_ga, "evaluate_genes", counted)
    sequence = [x[0], x[0], x[1], x[1], x[0], x[2], x[2]]  # the GA's best at each check
    confirmed: list[np.ndarray] = []
    checked = None
    for best in sequence:
        checked = seed_ga.confirm_best(p, ctx, best, checked, confirmed)
    assert len(calls) == 4  # x0, x1, x0 again (the best changed in between), x2
    verdicts = evaluate_genes(p, env, None, x).feasible
    assert verdicts[0] and not verdicts[1] and verdicts[2]
    assert [tuple(c) for c in confirmed] == [tuple(x[0]), tuple(x[0]), tuple(x[2])]
