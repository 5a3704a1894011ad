"""Every baseline as a planning method (`shiproute plan --method NAME`), for the registry.

Each adapter builds `BaselineInputs` from the planner's `MethodContext` (same problem,
environment, land mask and seed tracks the seed GA gets), runs the method and hands back the
single evaluated route. Metaheuristics use the context's wall-time budget; graph methods run
to completion (their effort is set by their resolution, not by time).
"""

from __future__ import annotations

from collections.abc import Callable

from ..method_context import MethodContext, MethodFn, MethodResult
from . import runners
from .inputs import BaselineInputs
from .metaheuristics import run_pymoo_method
from .result import BaselineResult

BaselineRun = Callable[[BaselineInputs, MethodContext], BaselineResult]


def _inputs(ctx: MethodContext) -> BaselineInputs:
    return BaselineInputs(ctx.problem, ctx.env, ctx.land, seed_tracks=tuple(ctx.seeds))


def _adapter(run: BaselineRun, seed_source: str) -> Callable[[MethodContext], MethodResult]:
    def method(ctx: MethodContext) -> MethodResult:
        r = run(_inputs(ctx), ctx)
        # MethodResult counts whole routes; graph searches' single legs are not routes
        return MethodResult(r.evaluation, seed_source, 0, r.route_evaluations)

    method.__doc__ = run.__doc__
    return method


def _pymoo(algorithm: str, seeded: bool, two_objective: bool = False) -> BaselineRun:
    def run(inp: BaselineInputs, ctx: MethodContext) -> BaselineResult:
        """pymoo algorithm on the seed GA's encoding within the wall-time budget."""
        return run_pymoo_method(inp, algorithm, None, ctx.rng, seeded, two_objective,
                                time_s=ctx.budget_s)

    return run


GRAPH_METHODS: dict[str, BaselineRun] = {
    "isochrone": lambda inp, ctx: runners.run_isochrone(inp),
    "dijkstra": lambda inp, ctx: runners.run_grid(inp, astar=False),
    "astar": lambda inp, ctx: runners.run_grid(inp, astar=True),
    "dijkstra_rpm": lambda inp, ctx: runners.run_two_stage(inp, astar=False),
    "astar_rpm": lambda inp, ctx: runners.run_two_stage(inp, astar=True),
    "ddp3": lambda inp, ctx: runners.run_ddp3(inp),
    "tc_astar": lambda inp, ctx: runners.run_tc_astar(inp),
}
PYMOO_METHODS: dict[str, BaselineRun] = {
    "nsga2": _pymoo("nsga2", False),
    "spea2": _pymoo("spea2", False),
    "pso": _pymoo("pso", False),
    "nsga2_seeded": _pymoo("nsga2", True),
    "spea2_seeded": _pymoo("spea2", True),
    "pso_seeded": _pymoo("pso", True),
    "nsga2_2obj": _pymoo("nsga2", True, two_objective=True),
}


def baseline_methods() -> dict[str, MethodFn]:
    """Every baseline by name, adapted to the planner's method interface."""
    methods: dict[str, MethodFn] = {}
    for name, run in GRAPH_METHODS.items():
        methods[name] = _adapter(run, "none")
    for name, run in PYMOO_METHODS.items():
        methods[name] = _adapter(run, "seeds" if "seeded" in name or "2obj" in name else "none")
    return methods
