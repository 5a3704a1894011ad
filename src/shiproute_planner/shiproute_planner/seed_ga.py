"""The seed GA, the planner's reference method: seed tracks (baseline, great circle, sea lanes,
bent variants, timed versions, previous plan and pool) turned into genes, the generic ask/tell
GA (islands, then one population) within the wall-time budget, and the exact final choice
checked against the coastline polygons."""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable

import numpy as np
from shiproute_core.flags import FLAG_LAND
from shiproute_core.geodesy import inverse

from .ga.islands import IslandGA, cross_track_rad
from .ga.loop import AskTellGA, GAConfig, SeedGA
from .ga.ranking import deb_order, is_better
from .geo.landmask import LandMask
from .geo.verify import land_crossings
from .method_context import Baseline, MethodContext, MethodResult, Progress, compute_baseline
from .plan_types import reasons_of
from .risk_choice import risk_choice
from .route.encoding import clip_genes, gene_bounds
from .route.environment import Environment
from .route.evaluation import RouteEvaluation
from .route.fast_eval import FastEvaluator, fast_evaluator
from .route.generate import evaluate_genes
from .route.member_eval import risk_evaluate
from .route.problem import RouteProblem
from .route.seeding import TrackSeed, great_circle_track, sea_lane_track, track_to_genes, via_track

EXACT_CHOICE_RESERVE_S = 0.25  # wall time kept for the exact final choice and dense land check
EXACT_CHOICE_SHARE = 0.28  # ... at most this share of a small budget (re-plans of 0.5 s)
EXACT_TOP_PER_S = 40.0  # final candidates re-evaluated exactly per second of budget (4..24)
DENSE_CHECKS = 12  # feasible final candidates given the dense land check, best first
EXACT_CHECK_EVERY = 15  # generations between exact confirmations of the GA's best
ISLAND_MIN_EVALUATIONS = 40_000  # islands only on searches this long (seed_ga.islands_pay)
ISLAND_MIN_BUDGET_S = 8.0
SHORT_SEARCH_POP = 30  # population of a shorter search
FRESH_SEEDS_MIN_BUDGET_S = 1.0  # a stale re-plan's fresh seeds cost ~0.1-0.2 s per span
FRESH_SEEDS_MIN_EVALUATIONS = 5_000
# RPM ramps (relative change from the first to the last leg / 2) of timed seed variants
TIMED_SLOPES = (-0.08, -0.04, 0.04, 0.08)


def seed_ga_method(ctx: MethodContext) -> MethodResult:
    """Seed GA: seeds (pool, previous plan, sea lane, great circle) + GA within the budget."""
    p, env = ctx.problem, ctx.env
    seeds = all_seeds(ctx)
    fast = fast_evaluator(p, env, ctx.land)
    risk = env.risk if fast is not None and fast.member_count > 1 else None

    def evaluate(x: np.ndarray) -> RouteEvaluation:
        """GA-loop evaluator: the compiled one when the environment allows it (on every
        ensemble member, reduced by the risk measure, when a risk measure is set)."""
        if risk is not None and fast is not None:
            return risk_evaluate(fast, risk, x)
        return fast.evaluate(x) if fast is not None else evaluate_genes(p, env, ctx.land, x)

    x_seed, sources = seed_genes(ctx, seeds, fast)
    x_seed, sources, offsets = best_seeds_first(p, x_seed, sources, evaluate)
    x_seed, sources, offsets, notes = fresh_seeds_if_stale(ctx, fast, evaluate, x_seed,
                                                           sources, offsets)
    ga = initial_ga(ctx, x_seed, offsets)
    # the exact evaluator confirms bests of one forecast only (a risk-aware best is a
    # measure over members the exact evaluator does not see)
    best_src, confirmed = run_ga(ctx, ga, evaluate, fast is not None and risk is None, sources)
    if risk is not None:  # the risk measure chooses, not the members' mean
        pop = ga.pop
        assert pop is not None  # the loop ran at least one generation
        best_x, final = risk_choice(p, env, ctx.land, pop, evaluate)
        return MethodResult(final, best_src, ga.generation, ga.evaluations, best_x.copy(),
                            notes)
    return dataclasses.replace(final_result(ctx, ga, confirmed, best_src), notes=notes)


def fresh_seeds_fit(ctx: MethodContext) -> bool:
    """Whether the span's search affords a cold plan's seeds (baseline, ~25 more tracks)."""
    if ctx.max_evaluations:
        return ctx.max_evaluations >= FRESH_SEEDS_MIN_EVALUATIONS
    return ctx.budget_s >= FRESH_SEEDS_MIN_BUDGET_S


def fresh_seeds_if_stale(ctx: MethodContext, fast: FastEvaluator | None,
                         evaluate: Callable[[np.ndarray], RouteEvaluation], x_seed: np.ndarray,
                         sources: list[str], offsets: np.ndarray
                         ) -> tuple[np.ndarray, list[str], np.ndarray, tuple[str, ...]]:
    """When no given seed (the previous plan on a new cycle, the pool's route) is feasible,
    a cold plan's seeds too (there already with a baseline): a route into the new cycle's
    storm is not repaired in a few generations. Returns them ranked, and the note why."""
    if not ctx.seeds or len(x_seed) == 0:
        return x_seed, sources, offsets, ()
    name = ctx.seeds[0].source
    given = np.flatnonzero([s.startswith(name) for s in sources])
    ev = evaluate(x_seed[given]) if given.size else None
    if ev is None or (ev.violation <= 0).any():
        return x_seed, sources, offsets, ()
    k = int(np.argmin(ev.violation))
    why = "; ".join(reasons_of(int(ev.flags[k]))) or "constraints violated"
    stale = f"re-plan: no route seeded from the {name} is feasible on this forecast ({why})"
    if ctx.baseline is not None:  # the cold plan's seeds are in already
        return x_seed, sources, offsets, (stale + "; searched from fresh seeds as well",)
    if not fresh_seeds_fit(ctx):
        budget = (f"{ctx.max_evaluations} evaluations" if ctx.max_evaluations
                  else f"{ctx.budget_s:.2f} s")
        return x_seed, sources, offsets, (
            f"{stale}; this span's budget ({budget}) was too short for fresh seeds: a "
            "longer budget may find a feasible route",)
    p = ctx.problem
    cold = dataclasses.replace(ctx, seeds=[], gene_seeds=[],
                               baseline=compute_baseline(p, ctx.env, ctx.land))
    more, more_sources = seed_genes(cold, all_seeds(cold), fast)
    x, names, off = best_seeds_first(p, np.concatenate([x_seed, more]), sources + more_sources,
                                     evaluate)
    return x, names, off, (stale + "; searched from fresh seeds as well",)


def all_seeds(ctx: MethodContext) -> list[TrackSeed]:
    """The given seeds, the baseline's tracks (when there is a baseline) and earlier/later
    versions of the first two given seeds."""
    seeds = list(ctx.seeds)
    base = ctx.baseline
    if base is None and not seeds:
        base = compute_baseline(ctx.problem, ctx.env, ctx.land)
    tracks = _seed_tracks(ctx, base) if base is not None else []
    for s in ctx.seeds[:2]:  # given seeds (previous plan, pool): also earlier/later versions
        for slope in TIMED_SLOPES:
            ramp = np.linspace(-1.0, 1.0, max(s.rpm.size, 1))
            tracks.append((f"{s.source}_timed", s.lon_deg, s.lat_deg, s.rpm * (1 + slope * ramp)))
    for name, lon, lat, rpm in tracks:
        seeds.append(TrackSeed(name, lon, lat, np.broadcast_to(rpm, lon.size - 1).copy()))
    return seeds


def seed_genes(ctx: MethodContext, seeds: list[TrackSeed], fast: FastEvaluator | None
               ) -> tuple[np.ndarray, list[str]]:
    """(genes, source names) of the seed tracks and of the ready gene seeds that fit."""
    p = ctx.problem
    x_seed = (track_to_genes(p, ctx.env, seeds, ctx.land, fast=fast) if seeds
              else np.empty((0, p.n_var)))
    sources = [s.source for s in seeds]
    for name, genes in ctx.gene_seeds:
        if genes.size == p.n_var and np.all(np.isfinite(genes)):
            x_seed = np.concatenate([x_seed, clip_genes(p, genes[None, :])])
            sources.append(name)
    return x_seed, sources


def best_seeds_first(p: RouteProblem, x_seed: np.ndarray, sources: list[str],
                     evaluate: Callable[[np.ndarray], RouteEvaluation]
                     ) -> tuple[np.ndarray, list[str], np.ndarray]:
    """Seeds ranked best first (the initial population jitters them most), their sources,
    and their cross-track offsets from the great circle (which island each goes to)."""
    if len(x_seed) <= 1:
        return x_seed, sources, np.zeros(len(x_seed))
    sev = evaluate(x_seed)
    order = deb_order(sev.violation, sev.objective)
    offsets = cross_track_rad(sev.lon_deg[order], sev.lat_deg[order],
                              (p.dep_lon_deg, p.dep_lat_deg), (p.arr_lon_deg, p.arr_lat_deg))
    return x_seed[order], [sources[i] for i in order], offsets


def islands_pay(ctx: MethodContext) -> bool:
    """Whether the search is long enough for islands: each island must get generations
    enough to refine its basin before the merge. Below ISLAND_MIN_EVALUATIONS (or its wall
    time at the compiled evaluator's ~5,000 evaluations/s) one population converges further:
    Busan -> Long Beach in the March storm at 14,000 evaluations (a 3 s plan), mean of three
    seeds: 614-615 t with three islands of 40, 611.4 t with one population of 80, 608.7 t of
    50, 607.4 t of 30 (602.3 t at 150,000 evaluations)."""
    if ctx.max_evaluations:
        return ctx.max_evaluations >= ISLAND_MIN_EVALUATIONS
    return ctx.budget_s >= ISLAND_MIN_BUDGET_S


def initial_ga(ctx: MethodContext, x_seed: np.ndarray, offsets: np.ndarray) -> AskTellGA:
    """Islands by side of the great circle when there are seeds and search enough, else one
    GA (of at most SHORT_SEARCH_POP on a short search)."""
    p = ctx.problem
    lo, hi = gene_bounds(p)
    cfg = ctx.ga_config or GAConfig()
    if len(x_seed) >= 2 * ctx.n_islands and ctx.n_islands > 1 and islands_pay(ctx):
        return IslandGA(lo, hi, p.n_stages, cfg, ctx.rng, x_seed, offsets, ctx.n_islands)
    if not islands_pay(ctx):
        cfg = dataclasses.replace(cfg, pop_size=min(cfg.pop_size, SHORT_SEARCH_POP),
                                  offspring=min(cfg.offspring, SHORT_SEARCH_POP))
    return SeedGA(lo, hi, p.n_stages, cfg, ctx.rng, x_seed)


def search_deadline_s(ctx: MethodContext) -> float:
    """Wall time of the GA loop: the budget less the time kept for the exact re-evaluation
    and dense land check of the final candidates."""
    return ctx.budget_s - min(EXACT_CHOICE_SHARE * ctx.budget_s, EXACT_CHOICE_RESERVE_S)


def merge_due(ctx: MethodContext, ga: IslandGA, merge_s: float) -> bool:
    """True when the islands are to become one population (their share of the search spent)."""
    if ga.merged:
        return False
    return (time.perf_counter() - ctx.t_start >= merge_s
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
           evaluate: Callable[[np.ndarray], RouteEvaluation], exact_check: bool,
           sources: list[str]) -> tuple[str, list[np.ndarray]]:
    """The ask/tell loop within the budget: (best seed's source, bests the exact evaluator
    confirmed along the way, the fallback when the final population sits where a boolean
    criterion flips between the two evaluators)."""
    p = ctx.problem
    confirmed: list[np.ndarray] = []
    deadline_s = search_deadline_s(ctx)
    merge_s = ctx.island_share * deadline_s
    best_src = "none"
    while True:
        if isinstance(ga, IslandGA) and merge_due(ctx, ga, merge_s):
            ga.merge()
        x = offspring(ctx, ga)
        ev = evaluate(x)
        ga.tell(x, ev.violation, ev.objective)
        if (exact_check and ga.generation % EXACT_CHECK_EVERY == 0 and ga.best[1] <= 0
                and evaluate_genes(p, ctx.env, ctx.land, ga.best[0][None, :]).feasible[0]):
            confirmed.append(ga.best[0].copy())
        if ga.generation == 0:
            best_src = first_best_source(ev, sources)
        _, v, f = ga.best
        elapsed = time.perf_counter() - ctx.t_start
        if ctx.progress is not None:
            ctx.progress(Progress(ctx.leg_index, ga.generation, ga.evaluations,
                                  f if v <= 0 else float("nan"), v, elapsed))
        if search_over(ctx, ga, elapsed, deadline_s):
            return best_src, confirmed


def final_result(ctx: MethodContext, ga: AskTellGA, confirmed: list[np.ndarray],
                 best_src: str) -> MethodResult:
    """The exact choice among the final population (and the confirmed bests), never worse
    than the constant-RPM baseline the GA was seeded with."""
    pop = ga.pop
    assert pop is not None  # the loop ran at least one generation
    top = min(24, len(pop), max(4, round(min(EXACT_TOP_PER_S * ctx.budget_s, 24.0))))
    pool_x = pop if not confirmed else np.concatenate([pop[:top], confirmed[::-1], pop[top:]])
    best_x, final = exact_choice(ctx.problem, ctx.env, ctx.land, pool_x, top=top)
    b = ctx.baseline
    if b is not None and is_better(
        float(b.evaluation.violation[0]), float(b.evaluation.objective[0]),
        float(final.violation[0]), float(final.objective[0]),
    ):
        return MethodResult(b.evaluation, "baseline", ga.generation, ga.evaluations, None)
    return MethodResult(final, best_src, ga.generation, ga.evaluations, best_x.copy())


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
    # the independent dense check (geodesic points every 500 m, all on the polygons) must
    # agree: the first feasible candidate that passes it wins
    first_bad: tuple[int, list[int]] | None = None
    for k in order[:DENSE_CHECKS]:
        if ev.violation[k] > 0:
            break
        bad = land_crossings(ev.lon_deg[k], ev.lat_deg[k], port_clearance_m=0.0,
                             contains=land.is_land)
        if not bad:
            return x[k].copy(), ev.take(int(k))
        first_bad = first_bad or (int(k), bad)
    if first_bad is None:
        k = int(order[0])
        return x[k].copy(), ev.take(k)
    k, bad = first_bad  # nothing passed: the best, flagged with the legs the check rejects
    return x[k].copy(), with_land_legs(ev.take(k), bad)


def with_land_legs(ev: RouteEvaluation, legs: list[int]) -> RouteEvaluation:
    """One-row evaluation with `legs` flagged as crossing land (violation 2 per leg)."""
    leg_flags = ev.leg_flags.copy()
    leg_flags[0, legs] |= np.uint32(FLAG_LAND)
    return dataclasses.replace(ev, leg_flags=leg_flags, flags=ev.flags | np.uint32(FLAG_LAND),
                               violation=ev.violation + 2.0 * len(legs))


def _seed_tracks(ctx: MethodContext, base: Baseline) -> list[tuple]:
    """Baseline, great circle, sea lane and sea lanes via bent midpoints, each with the
    baseline RPM scaled by track length (speed ~ RPM) so it arrives about on time."""
    p = ctx.problem
    length_b = float(base.evaluation.distance_m[0])

    def scaled(lon: np.ndarray, lat: np.ndarray) -> float:
        """Baseline RPM scaled by track length (speed ~ RPM) so the seed is about on time."""
        length = float(np.sum(inverse(lon[:-1], lat[:-1], lon[1:], lat[1:])[1]))
        return float(np.clip(base.rpm * length / max(length_b, 1.0), p.limits.rpm_min,
                             p.limits.rpm_max))

    tracks = [(base.name, base.lon_deg, base.lat_deg)]
    if not ctx.seeds:
        if base.name != "great_circle":
            tracks.append(("great_circle", *great_circle_track(p)))
        if base.name != "sea_lane":
            lane = sea_lane_track(p)
            if lane is not None:
                tracks.append(("searoute", *lane))
        if ctx.n_offset_seeds:
            # the baseline's port approaches + open-ocean great circles via points moved
            # north/south of the great circle at 1/3, 1/2 and 2/3 of the way
            g_lon, g_lat = great_circle_track(p, 7)
            spread = np.linspace(-ctx.offset_span_deg, ctx.offset_span_deg,
                                 ctx.n_offset_seeds + 1)
            spread = np.concatenate([spread[spread != 0.0], [-3.0, 3.0]])
            for j in (2, 3, 4):
                for d in spread:
                    mlat = float(np.clip(g_lat[j] + d, -p.limits.lat_bound_deg,
                                         p.limits.lat_bound_deg))
                    v = via_track(base.lon_deg, base.lat_deg, float(g_lon[j]), mlat)
                    tracks.append(("via_point", *v))
    out: list[tuple[str, np.ndarray, np.ndarray, float | np.ndarray]] = [
        (name, lon, lat, scaled(lon, lat)) for name, lon, lat in tracks]
    # the baseline track with RPM ramps: passing a storm earlier or later than the
    # constant-RPM schedule does is often cheaper than steering around it
    n_leg = base.lon_deg.size - 1
    ramp = np.linspace(-1.0, 1.0, max(n_leg, 1))
    for slope in TIMED_SLOPES:
        rpm = np.clip(base.rpm * (1.0 + slope * ramp), p.limits.rpm_min, p.limits.rpm_max)
        out.append(("baseline_timed", base.lon_deg, base.lat_deg, rpm))
    return out

