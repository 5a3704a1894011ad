"""Metaheuristic rows of the comparison at an equal route-evaluation budget.

The seed GA (the planner's `SeedGA`, driven here by evaluations instead of wall time) and the
pymoo algorithms all evaluate genes with `route.generate.evaluate_genes`, so a budget of N
evaluations means N routes generated and judged the same way for every algorithm.
"""

from __future__ import annotations

import time

import numpy as np

from ..ga.loop import GAConfig
from ..route.encoding import gene_bounds
from ..route.generate import evaluate_genes
from ..route.rta import constant_rpm_for_rta
from ..route.seeding import TrackSeed, great_circle_track, sea_lane_track, track_to_genes
from .inputs import BaselineInputs
from .pymoo_methods import run_pymoo
from .result import BaselineResult


def seed_genes(inp: BaselineInputs) -> np.ndarray:
    """Seed genes as the planner's seed GA builds them: the given seed tracks plus the great
    circle (and the sea lane when no other seed is given), each at the constant RPM meeting
    the RTA on its own track, converted by `track_to_genes`."""
    if inp.seed_genes is not None and len(inp.seed_genes):
        return np.atleast_2d(inp.seed_genes)
    p = inp.problem
    seeds = list(inp.seed_tracks)
    tracks = [("great_circle", *great_circle_track(p))]
    if not seeds:
        lane = sea_lane_track(p)
        if lane is not None:
            tracks.append(("searoute", *lane))
    for name, lon, lat in tracks:
        rpm, _ = constant_rpm_for_rta(p, inp.env, None, lon, lat, n_try=16, rounds=2)
        seeds.append(TrackSeed(name, lon, lat, np.full(lon.size - 1, rpm)))
    return track_to_genes(p, inp.env, seeds)


def _gene_evaluator(inp: BaselineInputs):
    p = inp.problem

    def evaluate(x: np.ndarray):
        ev = evaluate_genes(p, inp.env, inp.land, x)
        late_h = np.maximum(0.0, ev.eta_s - p.rta_s) / 3600.0
        rta_viol = np.where(late_h > 0, 1.0 + late_h, 0.0)
        return ev.fuel_t, ev.eta_s, ev.violation, rta_viol

    return evaluate


def run_seed_ga(inp: BaselineInputs, n_evaluations: int, rng: np.random.Generator,
                config: GAConfig | None = None) -> BaselineResult:
    """The planner's seed GA (`seed_ga.seed_ga_method`: its seeds, islands and final exact
    choice) stopped after `n_evaluations` route evaluations."""
    from ..method_context import MethodContext
    from ..seed_ga import seed_ga_method

    t0 = time.perf_counter()
    ctx = MethodContext(inp.problem, inp.env, inp.land, rng, budget_s=1e9, ga_config=config,
                        max_evaluations=n_evaluations)
    res = seed_ga_method(ctx)
    return BaselineResult("seed_ga", res.evaluation, time.perf_counter() - t0, True,
                          route_evaluations=res.evaluations, genes=res.genes)


def run_pymoo_method(inp: BaselineInputs, algorithm: str, n_evaluations: int | None,
                     rng: np.random.Generator, seeded: bool, two_objective: bool = False,
                     pop_size: int = 50, time_s: float | None = None) -> BaselineResult:
    """NSGA-II / SPEA2 / PSO on the gene encoding; `two_objective` = (ETA, fuel) NSGA-II.

    The budget is `n_evaluations` routes, or `time_s` of wall time if that is None."""
    t0 = time.perf_counter()
    p = inp.problem
    lo, hi = gene_bounds(p)
    seeds = seed_genes(inp) if seeded else None
    r = run_pymoo(algorithm, _gene_evaluator(inp), lo, hi, n_evaluations, rng, seeds,
                  pop_size=pop_size, two_objective=two_objective, rta_s=p.rta_s,
                  time_s=time_s)
    final = evaluate_genes(p, inp.env, inp.land, r.genes[None])
    name = (algorithm + "_2obj") if two_objective else algorithm + ("_seeded" if seeded else "")
    return BaselineResult(
        name, final, time.perf_counter() - t0, True, route_evaluations=r.evaluations,
        genes=r.genes,
        pareto_eta_s=r.pareto_eta_s if two_objective else None,
        pareto_fuel_t=r.pareto_fuel_t if two_objective else None,
    )
