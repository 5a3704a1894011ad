"""The seed GA, the planner's reference method: seed tracks (baseline, great circle, sea lanes,
bent variants, timed versions, previous plan and pool) turned into genes, the generic ask/tell
GA (islands, then one population) within the wall-time budget, and the exact final choice
checked against the finest coastline installed (GSHHG full: `geo.full_land`)."""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable

import numpy as np
from shiproute_core.flags import FLAG_LAND

from .ga.islands import IslandGA
from .ga.loop import AskTellGA, GAConfig, SeedGA
from .ga.ranking import deb_order, is_better
from .ga_refine import REFINE_EVERY, REFINE_ROUNDS, ga_share_of, refine_best
from .ga_seeds import all_seeds, best_seeds_first, bounded_seed_genes, fresh_seeds_if_stale
from .geo.full_land import final_land
from .geo.landmask import LandMask
from .method_context import MethodContext, MethodResult, Progress
from .risk_choice import risk_choice
from .risk_front import RiskFront, front_first, front_statement
from .route.encoding import gene_bounds
from .route.environment import Environment
from .route.evaluation import RouteEvaluation
from .route.fast_eval import FastEvaluator, fast_evaluator
from .route.generate import evaluate_genes
from .route.land_repair import land_legs
from .route.member_eval import risk_evaluate_outcomes
from .route.problem import RouteProblem
from .seeding_budget import seeding_budget
from .tile_allowance import TileAllowance, tile_allowance

EXACT_CHOICE_RESERVE_S = 0.25  # wall time kept for the exact final choice and dense land check
EXACT_CHOICE_SHARE = 0.28  # ... at most this share of a small budget (re-plans of 0.5 s)
EXACT_TOP_PER_S = 40.0  # final candidates re-evaluated exactly per second of budget (4..24)
DENSE_CHECKS = 12  # feasible final candidates given the dense land check, best first
RECORD_BEST_EVERY = 15  # generations between records of the GA's best for the final choice
SHORT_SEARCH_S = 1.0  # a search this short publishes a clean seed rather than repair land
# a risk-aware GA first runs on the members' mean forecast for this share of the budget and
# seeds itself with that run's best candidates
MEAN_PHASE_SHARE = 0.25
MEAN_PHASE_SEEDS = 8


def seed_ga_method(ctx: MethodContext) -> MethodResult:
    """Seed GA: seeds (pool, previous plan, sea lane, great circle) + GA within the budget."""
    p, env = ctx.problem, ctx.env
    allowance = tile_allowance(ctx.budget_s)
    seeds = all_seeds(ctx)
    fast = fast_evaluator(p, env, ctx.land)
    risk = env.risk if fast is not None and fast.member_count > 1 else None
    front = RiskFront(risk) if risk is not None else None

    def evaluate(x: np.ndarray) -> RouteEvaluation:
        """GA-loop evaluator: the compiled one when the environment allows it (on every
        ensemble member, reduced by the risk measure, when a risk measure is set, each
        candidate offered to the risk front)."""
        if risk is not None and fast is not None and front is not None:
            ev, out = risk_evaluate_outcomes(fast, risk, x)
            front.offer(x, out, ev.objective)
            return ev
        return fast.evaluate(x) if fast is not None else evaluate_genes(p, env, ctx.land, x)

    budget = seeding_budget(ctx.t_start, search_deadline_s(ctx))
    x_seed, sources, left_out = bounded_seed_genes(ctx, seeds, fast, budget)
    mean_gens = mean_evals = 0
    if risk is not None and fast is not None:
        x_seed, sources, mean_gens, mean_evals = with_mean_optimum(ctx, fast, x_seed, sources,
                                                                   allowance)
        ctx = dataclasses.replace(ctx, max_evaluations=max(
            ctx.max_evaluations - mean_evals, 1) if ctx.max_evaluations else 0)
    x_seed, sources, offsets = best_seeds_first(p, x_seed, sources, evaluate)
    x_seed, sources, offsets, notes = fresh_seeds_if_stale(
        ctx, fast, evaluate, x_seed, sources, offsets, budget)
    notes = (*left_out, *notes)
    ga = initial_ga(ctx, x_seed, offsets)
    # bests of one forecast only are kept for the exact final choice (a risk-aware best is
    # a measure over members the exact evaluator does not see)
    best_src, recorded = run_ga(ctx, ga, evaluate, fast is not None and risk is None, sources,
                                allowance)
    notes = (*notes, *allowance.statement())
    if risk is not None and fast is not None and front is not None:
        # the risk measure chooses, not the members' mean: the front's best within the
        # bounds first (the GA's elitism keeps it too), then the final population
        pop = ga.pop
        assert pop is not None  # the loop ran at least one generation
        best_x, final = risk_choice(p, env, ctx.land, front_first(front, pop), evaluate)
        return MethodResult(final, best_src, mean_gens + ga.generation,
                            mean_evals + ga.evaluations, best_x.copy(),
                            (*notes, *front_statement(fast, risk, front, best_x)))
    res = final_result(ctx, ga, recorded, best_src, x_seed)
    return dataclasses.replace(res, notes=(*notes, *res.notes))


def with_mean_optimum(ctx: MethodContext, fast: FastEvaluator, x_seed: np.ndarray,
                      sources: list[str], allowance: TileAllowance
                      ) -> tuple[np.ndarray, list[str], int, int]:
    """The seeds plus the best of a GA run on the members' mean forecast (a
    `MEAN_PHASE_SHARE` of the budget, its generations 1/M the cost of the members' ones):
    the risk-aware GA starts from the plan a mean-forecast planner would make, so (elitist)
    it never ends worse than it by its own ranking. Returns (genes, sources, generations,
    evaluations) of that run."""
    sub = dataclasses.replace(
        ctx, budget_s=MEAN_PHASE_SHARE * ctx.budget_s, progress=None,
        max_evaluations=round(MEAN_PHASE_SHARE * ctx.max_evaluations))
    xs, src, offsets = best_seeds_first(ctx.problem, x_seed, sources, fast.evaluate)
    ga = initial_ga(sub, xs, offsets)
    run_ga(sub, ga, fast.evaluate, False, src, allowance)
    pop = ga.pop  # best first (Deb order over all islands)
    assert pop is not None  # the loop ran at least one generation
    top = pop[:MEAN_PHASE_SEEDS]
    return (np.concatenate([top, x_seed]), [*["mean_forecast_ga"] * len(top), *sources],
            ga.generation, ga.evaluations)


def initial_ga(ctx: MethodContext, x_seed: np.ndarray, offsets: np.ndarray) -> AskTellGA:
    """Islands by side of the great circle when there are seeds enough, else one GA."""
    p = ctx.problem
    lo, hi = gene_bounds(p)
    cfg = ctx.ga_config or GAConfig()
    if len(x_seed) >= 2 * ctx.n_islands and ctx.n_islands > 1:
        return IslandGA(lo, hi, p.n_stages, cfg, ctx.rng, x_seed, offsets, ctx.n_islands)
    return SeedGA(lo, hi, p.n_stages, cfg, ctx.rng, x_seed)


def search_deadline_s(ctx: MethodContext) -> float:
    """Wall time of the GA loop: the budget less the time kept for the exact re-evaluation
    and dense land check of the final candidates."""
    return ctx.budget_s - min(EXACT_CHOICE_SHARE * ctx.budget_s, EXACT_CHOICE_RESERVE_S)


def merge_due(ctx: MethodContext, ga: IslandGA, merge_s: float, elapsed_s: float) -> bool:
    """True when the islands are to become one population (their share of the search spent)."""
    if ga.merged:
        return False
    return (elapsed_s >= merge_s
            or ga.generation >= ctx.island_share * ctx.max_generations
            or 0 < ctx.max_evaluations * ctx.island_share <= ga.evaluations)


def offspring(ctx: MethodContext, ga: AskTellGA) -> np.ndarray:
    """The next genes to evaluate: the GA's offspring with local moves round each part's best,
    cut to what an evaluation budget leaves."""
    x = ga.ask()
    if ga.pop is None:
        return x
    lo, hi = gene_bounds(ctx.problem)
    parts = ga.parts() if isinstance(ga, IslandGA) else [(slice(0, len(x)), ga)]
    for sl, isl in parts:
        _rpm_scaled_best(x[sl], isl.best[0], ctx.problem.n_stages, lo, hi, ctx.rng)
    if ctx.max_evaluations:
        # an evaluation budget is exact once every island has its first population (a
        # budget smaller than that still evaluates the whole first population)
        x = x[: max(ctx.max_evaluations - ga.evaluations, 1)]
    return x


def first_best_source(ev: RouteEvaluation, sources: list[str]) -> str:
    """The source of the best seed of the first population ("none" without seeds)."""
    n = len(sources)
    order = np.lexsort((ev.objective[:n], ev.violation[:n] > 0, ev.violation[:n]))
    return sources[int(order[0])] if sources else "none"


def search_over(ctx: MethodContext, ga: AskTellGA, elapsed_s: float, deadline_s: float) -> bool:
    """True when time, generations, evaluations, stall or a cancel end the search."""
    return bool(elapsed_s >= deadline_s or ga.generation >= ctx.max_generations
                or ctx.cancelled() or 0 < ctx.max_evaluations <= ga.evaluations
                or (ctx.stall_generations and ga.stalled(ctx.stall_generations)))


def run_ga(ctx: MethodContext, ga: AskTellGA,
           evaluate: Callable[[np.ndarray], RouteEvaluation], record: bool,
           sources: list[str], allowance: TileAllowance) -> tuple[str, list[np.ndarray]]:
    """The ask/tell loop within the budget, its clock less the `allowance` for coastline
    tiles built meanwhile: (best seed's source, the GA's feasible bests along the way when
    `record`, the exact final choice's fallback when the final population sits where a
    boolean criterion flips between the two evaluators)."""

    def elapsed_s() -> float:
        return time.perf_counter() - ctx.t_start - allowance.excused_s()

    recorded: list[np.ndarray] = []
    search_s = search_deadline_s(ctx)
    # the loop's share of the search; the rest refines its best (ga_refine)
    deadline_s, loop_evals = ga_share_of(ctx, search_s)
    whole, ctx = ctx, dataclasses.replace(ctx, max_evaluations=loop_evals)
    merge_s = ctx.island_share * deadline_s
    best_src = "none"
    while True:
        if isinstance(ga, IslandGA) and merge_due(ctx, ga, merge_s, elapsed_s()):
            ga.merge()
        x = offspring(ctx, ga)
        ev = evaluate(x)
        ga.tell(x, ev.violation, ev.objective)
        if record and ga.generation % RECORD_BEST_EVERY == 0 and ga.best[1] <= 0:
            record_best(ga.best[0], recorded)
        if ga.generation == 0:
            best_src = first_best_source(ev, sources)
        elif ga.generation % REFINE_EVERY == 0:  # memetic step: descend from the best
            refine_best(ctx, ga, evaluate, deadline_s + allowance.excused_s(), REFINE_ROUNDS)
        _, v, f = ga.best
        elapsed = elapsed_s()
        if ctx.progress is not None:
            ctx.progress(Progress(ctx.leg_index, ga.generation, ga.evaluations,
                                  f if v <= 0 else float("nan"), v, elapsed))
        if search_over(ctx, ga, elapsed, deadline_s):
            if ctx is whole or whole.cancelled():
                return best_src, recorded
            refine_best(whole, ga, evaluate, search_s + allowance.excused_s())
            # what the refinement left (it stops when it gains nothing) goes back to the GA
            ctx, deadline_s = whole, search_s
            if search_over(ctx, ga, elapsed_s(), deadline_s):
                return best_src, recorded


def record_best(best: np.ndarray, recorded: list[np.ndarray]) -> None:
    """Append a copy of `best` to `recorded` unless it is the last one there (the GA's best
    unchanged since). The exact evaluator judges them all at once in the final choice, only
    when no final candidate passes: its cost is per call (~18 ms for one route or thirty),
    and a call per record took ~8 % of a plan's CPU."""
    if not recorded or not np.array_equal(best, recorded[-1]):
        recorded.append(best.copy())


def final_result(ctx: MethodContext, ga: AskTellGA, recorded: list[np.ndarray],
                 best_src: str, seeds: np.ndarray | None = None) -> MethodResult:
    """The exact choice among the final population (and the recorded bests), never worse
    than the constant-RPM baseline the GA was seeded with; after a short search whose
    choice touches land at full resolution, the best of its `seeds` that passes (see
    `clean_seed`)."""
    pop = ga.pop
    assert pop is not None  # the loop ran at least one generation
    top = min(24, len(pop), max(4, round(min(EXACT_TOP_PER_S * ctx.budget_s, 24.0))))
    pool_x = pop if not recorded else np.concatenate([pop[:top], recorded[::-1], pop[top:]])
    best_x, final = exact_choice(ctx.problem, ctx.env, ctx.land, pool_x, top=top)
    clean = clean_seed(ctx, seeds, final)
    said: tuple[str, ...] = ()
    if clean is not None:
        best_x, final = clean
        said = ("search: its best route touched land at full resolution; with a "
                f"{ctx.budget_s:.2f}-s search the best seed that passes the check was taken "
                "instead of a detour round the land",)
    b = ctx.baseline
    if b is not None and better_than(b.evaluation, final):
        # the baseline wins only through the same dense land check as the GA's candidates
        # (its compiled verdict samples legs too sparsely for an islet like Kojima off Tsugaru)
        base = b.evaluation
        bad = [] if ctx.land is None else dense_land_legs(
            base.lon_deg[0], base.lat_deg[0], ctx.problem.port_clearance_m)
        base = with_land_legs(base, bad) if bad else base
        if better_than(base, final):
            return MethodResult(base, "baseline", ga.generation, ga.evaluations, None)
    return MethodResult(final, best_src, ga.generation, ga.evaluations, best_x.copy(),
                        notes=said)


def clean_seed(ctx: MethodContext, seeds: np.ndarray | None, final: RouteEvaluation
               ) -> tuple[np.ndarray, RouteEvaluation] | None:
    """For a re-plan's search shorter than SHORT_SEARCH_S whose exact choice the dense
    check put on land: the best feasible seed (the previous route, its repairs) that passes
    the same check, or None. The land repair of the choice (a detour on a fine grid,
    ~0.05-0.2 s) would cost a 0.5-s re-plan its budget; a cold plan keeps the repair."""
    if (ctx.land is None or seeds is None or len(seeds) == 0
            or ctx.budget_s >= SHORT_SEARCH_S or not int(final.flags[0]) & FLAG_LAND
            or not any(s.source == "previous_plan" for s in ctx.seeds)):
        return None  # not a re-plan's short search, or nothing to replace
    p = ctx.problem
    ev = evaluate_genes(p, ctx.env, ctx.land, seeds)
    for k in deb_order(ev.violation, ev.objective)[:DENSE_CHECKS]:
        if ev.violation[k] > 0:
            break
        if not dense_land_legs(ev.lon_deg[k], ev.lat_deg[k], p.port_clearance_m):
            return seeds[k].copy(), ev.take(int(k))
    return None


def better_than(a: RouteEvaluation, b: RouteEvaluation) -> bool:
    """Whether route evaluation `a` ranks before `b` (Deb's rules on their first routes)."""
    return is_better(float(a.violation[0]), float(a.objective[0]),
                     float(b.violation[0]), float(b.objective[0]))


def _rpm_scaled_best(x: np.ndarray, best: np.ndarray, n: int, lo: np.ndarray, hi: np.ndarray,
                     rng: np.random.Generator) -> None:
    """Local moves in place on the last eighth of offspring `x`, copies of the population's
    best: all RPMs scaled by ~0.4 % (trades ETA slack for fuel and back), and in every other
    copy the stage RPMs also pulled part of the way to their mean (fuel is convex in speed,
    so an even schedule is cheaper unless the weather says otherwise)."""
    if len(x) <= 8:
        return
    k = max(4, len(x) // 8)
    x[-k:] = best
    rpm = x[-k:, n:]
    even = rpm[::2]
    even -= rng.uniform(0.0, 1.0, size=(even.shape[0], 1)) * (
        even - even.mean(axis=1, keepdims=True))
    rpm *= 1.0 + rng.normal(0.0, 0.004, size=(k, 1))
    x[-k:] = np.clip(x[-k:], lo, hi)


def exact_choice(p: RouteProblem, env: Environment, land: LandMask, pop: np.ndarray,
                 top: int = 24) -> tuple[np.ndarray, RouteEvaluation]:
    """Best of the final population re-evaluated with the exact evaluator (pyproj geodesics).

    The GA's compiled evaluator agrees to metres per leg, but a route tuned to arrive just on
    time may miss the RTA by minutes in the exact one, and one that arrives early wastes
    fuel: the `top` best and copies of the best with all RPMs scaled by -3..+1 % are
    evaluated exactly and the best of them returned."""
    n = p.n_stages
    lo, hi = gene_bounds(p)
    cand = [pop[:top]]
    # slower copies spend ETA slack (fuel ~ speed^2 per distance), faster ones repair a
    # minutes-late arrival of the compiled evaluator's optimum
    scales = np.array([0.97, 0.98, 0.985, 0.99, 0.995, 1.001, 1.002, 1.004, 1.007, 1.01])
    bumped = np.repeat(pop[:1], scales.size, axis=0)
    bumped[:, n:] *= scales[:, None]
    cand.append(np.clip(bumped, lo, hi))
    x = np.concatenate(cand)
    ev = evaluate_genes(p, env, land, x)
    if not ev.feasible.any() and len(pop) > top:
        # boolean criteria (IMO resonances, land) can flip between the two evaluators at
        # the edge of feasibility: look at the rest of the population before giving up
        x = np.concatenate([x, pop[top:]])
        ev = evaluate_genes(p, env, land, x)
    order = deb_order(ev.violation, ev.objective)
    if land is None:
        k = int(order[0])
        return x[k].copy(), ev.take(k)
    # the independent dense check (the route check's geodesic points, all on the polygons) must
    # agree: the first feasible candidate that passes it wins
    first_bad: tuple[int, list[int]] | None = None
    for k in order[:DENSE_CHECKS]:
        if ev.violation[k] > 0:
            break
        bad = dense_land_legs(ev.lon_deg[k], ev.lat_deg[k], p.port_clearance_m)
        if not bad:
            return x[k].copy(), ev.take(int(k))
        first_bad = first_bad or (int(k), bad)
    if first_bad is None:
        k = int(order[0])
        return x[k].copy(), ev.take(k)
    k, bad = first_bad  # nothing passed: the best, flagged with the legs the check rejects
    return x[k].copy(), with_land_legs(ev.take(k), bad)


def dense_land_legs(lon_deg: np.ndarray, lat_deg: np.ndarray,
                    port_clearance_m: float = 0.0) -> list[int]:
    """Legs with land at the route check's own sample points (geodesic, every 0.25 NM) on
    the finest coastline installed, not the optimiser's mask: a crossing of an islet shorter
    than a coarser spacing, or missing from a coarser coastline, would pass there and fail
    at the final check."""
    lon = np.unwrap(np.asarray(lon_deg, dtype=float), period=360.0)
    # the final check's own pass (`land_repair.land_legs`: one geodesic pass for all legs)
    return land_legs(lon, np.asarray(lat_deg, dtype=float), final_land().contains,
                     port_clearance_m, port_clearance_m)


def with_land_legs(ev: RouteEvaluation, legs: list[int]) -> RouteEvaluation:
    """One-row evaluation with `legs` flagged as crossing land (violation 2 per leg)."""
    leg_flags = ev.leg_flags.copy()
    leg_flags[0, legs] |= np.uint32(FLAG_LAND)
    return dataclasses.replace(ev, leg_flags=leg_flags, flags=ev.flags | np.uint32(FLAG_LAND),
                               violation=ev.violation + 2.0 * len(legs))

