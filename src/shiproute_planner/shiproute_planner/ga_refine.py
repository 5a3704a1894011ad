"""The seed GA's last step: the best route refined by projected descent (`ga.polish`) in a
share of the search's time or evaluations, and put back into the population before the
exact final choice."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .ga.loop import AskTellGA
from .ga.polish import PolishConfig, PolishResult, polish
from .method_context import MethodContext
from .route.encoding import gene_bounds
from .route.evaluation import RouteEvaluation
from .route.problem import RouteProblem

# share of the search's wall time (or evaluations) kept for the last refinement; what it
# leaves unused (it stops when it gains nothing, or at once while no route is feasible)
# goes back to the GA. 0.12 -> 0.25 with heading descent: Busan -> Long Beach storm, 3-s
# cold plans of seeds 0-7, mean 610.7 -> 609.8 t, worst 613.4 -> 610.8 t (60-s runs ~606 t)
REFINE_SHARE = 0.25
REFINE_EVERY = 10  # generations between short refinements of the best during the search
REFINE_ROUNDS = 3  # descent rounds of such a short refinement


def ga_share_of(ctx: MethodContext, deadline_s: float) -> tuple[float, int]:
    """(wall-time deadline [s after the start], evaluation budget, 0 = none) of the GA loop
    itself: the search's less what the refinement keeps."""
    evals = round(ctx.max_evaluations * (1.0 - REFINE_SHARE)) if ctx.max_evaluations else 0
    return deadline_s * (1.0 - REFINE_SHARE), max(evals, 1) if ctx.max_evaluations else 0


def refine_best(ctx: MethodContext, ga: AskTellGA,
                evaluate: Callable[[np.ndarray], RouteEvaluation],
                deadline_s: float, max_rounds: int = 0) -> PolishResult | None:
    """Refine the GA's best until `deadline_s` (s after the start) or the evaluations left,
    and inject the result into the population (it never ranks below the best it started
    from). None when no time or evaluation is left."""
    p = ctx.problem
    left = ctx.max_evaluations - ga.evaluations if ctx.max_evaluations else 0
    if (ctx.max_evaluations and left < 2) or ga.best[1] > 0:
        return None  # no evaluations left, or no feasible best yet (feasibility is the GA's)

    def objective_of(x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        ev = evaluate(x)
        return ev.violation, ev.objective, ev.eta_s

    lo, hi = gene_bounds(p)
    x0 = ga.best[0]
    cfg = PolishConfig(with_headings=descend_headings(p, max_rounds),
                       max_rounds=max_rounds or PolishConfig.max_rounds)
    r = polish(x0, objective_of, lo, hi, p.n_stages, p.rta_s, ctx.t_start + deadline_s, left,
               cfg)
    ga.inject(r.x[None, :], np.array([r.violation]), np.array([r.objective]), r.evaluations)
    return r


def descend_headings(problem: RouteProblem, max_rounds: int) -> bool:
    """Whether a refinement descends on the heading genes too: only the last one (a short
    memetic step gains on the speed profile, where fuel is nearly convex) and only without
    no-go or penalty zones (heading descent finds the corners between the evaluator's 17
    samples of a zone per leg and cuts them; land is walked whole, so it cannot)."""
    zones = problem.limits.zones
    return max_rounds == 0 and (zones is None or not zones.zones)
