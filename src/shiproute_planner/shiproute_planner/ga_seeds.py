"""The seed GA's starting population: the seed tracks (given, baseline, great circle, sea
lane, bent via points, timed variants), their genes ranked best first, and fresh seeds when a
re-plan's given seeds are all infeasible on a new forecast."""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable

import numpy as np
from shiproute_core.geodesy import inverse

from .detour_seeds import RETIMED_ROWS, broken_legs, detour_genes, retimed_genes
from .ga.islands import cross_track_rad
from .ga.ranking import deb_order
from .method_context import Baseline, MethodContext, compute_baseline
from .plan_types import reasons_of
from .route.encoding import clip_genes, gene_bounds
from .route.evaluation import RouteEvaluation
from .route.fast_eval import FastEvaluator
from .route.problem import RouteProblem
from .route.seeding import TrackSeed, great_circle_track, sea_lane_track, track_to_genes, via_track
from .seeding_budget import SeedingBudget, unbounded
from .track_repairs import REPAIR_FAN_DEG, REPAIR_FAN_N, track_repairs

FRESH_SEEDS_MIN_BUDGET_S = 1.0  # a stale re-plan's fresh seeds cost ~0.1-0.2 s per span
FRESH_SEEDS_MIN_EVALUATIONS = 5_000
MIN_COLD_TRACKS = 3  # fewer cold seeds than this are not worth a conversion pass
REPAIRS_KEPT = 12  # repaired stale seeds (detours, retimed) that enter the first population
# RPM ramps (relative change from the first to the last leg / 2) of timed seed variants
TIMED_SLOPES = (-0.08, -0.04, 0.04, 0.08)


def fresh_seeds_fit(ctx: MethodContext) -> bool:
    """Whether the span's search is long enough for a cold plan's seeds (baseline, ~25
    more tracks) after the repairs of a stale re-plan's seeds."""
    if ctx.max_evaluations:
        return ctx.max_evaluations >= FRESH_SEEDS_MIN_EVALUATIONS
    return ctx.budget_s >= FRESH_SEEDS_MIN_BUDGET_S


def fresh_seeds_if_stale(ctx: MethodContext, fast: FastEvaluator | None,
                         evaluate: Callable[[np.ndarray], RouteEvaluation], x_seed: np.ndarray,
                         sources: list[str], offsets: np.ndarray,
                         budget: SeedingBudget | None = None
                         ) -> tuple[np.ndarray, list[str], np.ndarray, tuple[str, ...]]:
    """When no given seed (the previous plan on a new cycle, the pool's route) is feasible,
    repairs of them and a cold plan's seeds (great circle, sea lane, via points north and
    south, the baseline): a route into the new cycle's storm is not repaired in a few
    generations, and a re-plan is to end feasible where a cold plan from the ship would.
    Seeds are built only while `budget` (the seeding phase's share of the span) lasts: the
    best so far go to the GA, and the plan says what was left out. Returns them ranked, and
    the note why."""
    if not ctx.seeds or len(x_seed) == 0:
        return x_seed, sources, offsets, ()
    budget = budget or unbounded()
    name = ctx.seeds[0].source
    given = np.flatnonzero([s.startswith(name) for s in sources])
    ev = evaluate(x_seed[given]) if given.size else None
    if ev is None or (ev.violation <= 0).any():
        return x_seed, sources, offsets, ()
    k = int(np.argmin(ev.violation))
    why = "; ".join(reasons_of(int(ev.flags[k]))) or "constraints violated"
    stale = f"re-plan: no route seeded from the {name} is feasible on this forecast ({why})"
    p = ctx.problem
    # the repairs of the given seeds first (cheap, and what a short search lives on), then
    # a cold plan's seeds while the seeding budget lasts (a re-plan is to end feasible
    # where a cold plan from the ship would); a short wall-time search (a 0.5-s re-plan's
    # ~0.3-s span) has no room for ~0.1-0.2 s of cold seeds after its repairs
    fresh = ""
    per_track_s = budget.elapsed_s() / max(len(sources), 1)  # the given seeds' conversion
    x_seed, sources, said = with_repairs(ctx, fast, x_seed, sources, given, ev, evaluate,
                                         budget)
    if (fresh_seeds_fit(ctx) or ctx.max_evaluations) and not budget.spent():
        x_seed, sources, fresh = with_cold_seeds(ctx, fast, x_seed, sources, budget,
                                                 per_track_s)
    if budget.spent():
        said += f" ({spent_words(budget)})"
    if not fresh:
        fresh = ("; no room left for a cold plan's seeds in this span's seeding share ("
                 f"{budget.share_s():.2f} s): a longer budget may find a feasible route")
    x, names, off = best_seeds_first(p, x_seed, sources, evaluate)
    return x, names, off, (stale + said + fresh,)


def with_cold_seeds(ctx: MethodContext, fast: FastEvaluator | None, x_seed: np.ndarray,
                    sources: list[str], budget: SeedingBudget, per_track_s: float
                    ) -> tuple[np.ndarray, list[str], str]:
    """The seeds plus the seeds a cold plan from the same start would have (baseline, great
    circle, sea lane, via points north and south) that are not in yet, as many as the
    seeding budget's rest affords at `per_track_s` per track (the given seeds' conversion
    cost: one conversion cannot be stopped half way), and the plan's word ("": no room for
    them in the seeding share)."""
    p = ctx.problem
    base = ctx.baseline or compute_baseline(p, ctx.env, ctx.land)
    cold = dataclasses.replace(ctx, seeds=[], gene_seeds=[], baseline=base)
    present = set(sources)
    tracks = [s for s in all_seeds(cold) if s.source not in present]
    if not tracks:
        return x_seed, sources, "; a cold plan's seeds are all among them already"
    left_s = budget.deadline_s - time.perf_counter()
    # a search without a deadline (an evaluation budget only) affords every track
    fit = (len(tracks) if per_track_s <= 0 or not math.isfinite(left_s)
           else min(len(tracks), int(left_s / per_track_s)))
    if fit < MIN_COLD_TRACKS:
        return x_seed, sources, ""
    kept = affordable(tracks, fit)
    more, more_sources = seed_genes(cold, kept, fast)
    said = ("; searched from a cold plan's fresh seeds as well" if len(kept) == len(tracks)
            else f"; searched from {len(kept)} of a cold plan's {len(tracks)} fresh seeds as "
            "well (the seeding share's rest)")
    return np.concatenate([x_seed, more]), sources + more_sources, said


def affordable(tracks: list[TrackSeed], n: int) -> list[TrackSeed]:
    """At most `n` of `tracks`: the first two (great circle, sea lane) and the rest (via
    points north and south at three places) evenly spread."""
    if n >= len(tracks):
        return tracks
    head, rest = tracks[:2], tracks[2:]
    pick = np.unique(np.linspace(0, len(rest) - 1, max(n - len(head), 0)).round().astype(int))
    return head[:n] + [rest[i] for i in pick] if rest else head[:n]


def spent_words(budget: SeedingBudget) -> str:
    """What the plan says when the seeding phase ran out of its share."""
    return (f"seeding stopped after {budget.elapsed_s():.2f} s, its share "
            f"({budget.share_s():.2f} s) of the search spent: the best seeds so far taken")


def with_repairs(ctx: MethodContext, fast: FastEvaluator | None, x_seed: np.ndarray,
                 sources: list[str], given: np.ndarray, ev: RouteEvaluation,
                 evaluate: Callable[[np.ndarray], RouteEvaluation], budget: SeedingBudget
                 ) -> tuple[np.ndarray, list[str], str]:
    """The seeds plus the best REPAIRS_KEPT repairs of the given ones (`ev` their
    evaluation): the least broken one's track re-timed and its broken stretch shifted
    sideways (`track_repairs`, while `budget` lasts), detours round its broken legs in gene
    space and, when no track repair is feasible, the few least broken and the detours
    retimed in gene space; only a few are kept, so the population keeps the other seeds'
    diversity (a hundred near-copies of the stale route hold the search in its basin).
    Returns the seeds unranked (the caller ranks them once) and what the plan says."""
    p = ctx.problem
    lo, hi = gene_bounds(p)
    best = given[np.argsort(ev.violation, kind="stable")[:RETIMED_ROWS]]
    k = int(np.argmin(ev.violation))
    bent = detour_genes(x_seed[given[k]], p.n_stages, broken_legs(ev, k), lo, hi)
    tracked, names, fixed = track_repairs(p, ctx.env, ctx.land, fast, ev, k, evaluate,
                                          budget.spent, budget.overrun)
    detour = f"{sources[given[k]]}_detour"
    cand = np.concatenate([tracked, bent])
    names += [detour] * len(bent)
    if not fixed:  # gene-space re-timing too (small factors: minutes lost to the stages)
        base = np.concatenate([x_seed[best], bent])
        retimed = retimed_genes(base, p.n_stages, lo, hi)
        base_names = [f"{sources[i]}_retimed" for i in best] + [f"{detour}_retimed"] * len(bent)
        cand = np.concatenate([cand, retimed])
        names += base_names * (len(retimed) // len(base))
    said = ("; re-timed, shifted and detoured versions of it seeded too" if len(tracked)
            else "; detoured and re-timed versions of it seeded too, no track repairs")
    if not len(cand):
        return x_seed, sources, said
    rev = evaluate(cand)
    keep = deb_order(rev.violation, rev.objective)[:REPAIRS_KEPT]
    return (np.concatenate([x_seed, cand[keep]]), sources + [names[i] for i in keep], said)


def all_seeds(ctx: MethodContext) -> list[TrackSeed]:
    """The given seeds, the baseline's tracks (when there is a baseline) and earlier/later
    versions of the first two given seeds."""
    seeds = list(ctx.seeds)
    base = ctx.baseline
    if base is None and not seeds:
        base = compute_baseline(ctx.problem, ctx.env, ctx.land)
    tracks = seed_tracks(ctx, base) if base is not None else []
    for s in ctx.seeds[:2]:  # given seeds (previous plan, pool): also earlier/later versions
        for slope in TIMED_SLOPES:
            ramp = np.linspace(-1.0, 1.0, max(s.rpm.size, 1))
            tracks.append((f"{s.source}_timed", s.lon_deg, s.lat_deg, s.rpm * (1 + slope * ramp)))
    for name, lon, lat, rpm in tracks:
        seeds.append(TrackSeed(name, lon, lat, np.broadcast_to(rpm, lon.size - 1).copy()))
    return seeds


def seed_genes(ctx: MethodContext, seeds: list[TrackSeed], fast: FastEvaluator | None
               ) -> tuple[np.ndarray, list[str]]:
    """(genes, source names) of the seed tracks and of the ready gene seeds that fit; a
    search shorter than FRESH_SEEDS_MIN_BUDGET_S (a re-plan's span) converts its seeds, all
    tracks a plan already sailed or repairs of them, with the repairs' narrower fan."""
    p = ctx.problem
    narrow = bool(seeds) and not fresh_seeds_fit(ctx) and ctx.baseline is None
    x_seed = (track_to_genes(p, ctx.env, seeds, ctx.land, fast=fast,
                             fan_deg=REPAIR_FAN_DEG if narrow else 60.0,
                             fan_n=REPAIR_FAN_N if narrow else 13) if seeds
              else np.empty((0, p.n_var)))
    sources = [s.source for s in seeds]
    for name, genes in ctx.gene_seeds:
        if genes.size == p.n_var and np.all(np.isfinite(genes)):
            x_seed = np.concatenate([x_seed, clip_genes(p, genes[None, :])])
            sources.append(name)
    return x_seed, sources


def bounded_seed_genes(ctx: MethodContext, seeds: list[TrackSeed], fast: FastEvaluator | None,
                       budget: SeedingBudget) -> tuple[np.ndarray, list[str], tuple[str, ...]]:
    """`seed_genes` of a re-plan's seeds within the seeding share: the given seeds, the
    baseline and the other tracks first, their timed variants (earlier/later copies) only
    while `budget` lasts, in the order `seeds` gives them; and the plan's words when timed
    variants were left out. A conversion cannot be stopped half way, and under load the
    given seeds' one conversion took 1 s of a 3-s re-plan whose seeding share was 0.3 s.
    A cold plan (no given seeds) converts its seeds in one pass, as before."""
    timed = [i for i, s in enumerate(seeds) if s.source.endswith("_timed")]
    if not ctx.seeds or not timed:
        x, names = seed_genes(ctx, seeds, fast)
        return x, names, ()
    core = [i for i in range(len(seeds)) if i not in set(timed)]
    x_core, names_core = seed_genes(ctx, [seeds[i] for i in core], fast)
    if budget.spent():
        return x_core, names_core, (
            f"seeding: {len(timed)} timed copies of the seed tracks left out (the seeding "
            f"share, {budget.share_s():.2f} s, was spent converting the others)",)
    x_timed, _ = seed_genes(dataclasses.replace(ctx, gene_seeds=[]),
                            [seeds[i] for i in timed], fast)
    n = len(seeds)
    x = np.empty((n + len(x_core) - len(core), x_core.shape[1]))
    x[core] = x_core[:len(core)]
    x[timed] = x_timed
    x[n:] = x_core[len(core):]  # the ready gene seeds come after the tracks
    return x, [s.source for s in seeds] + names_core[len(core):], ()


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


def seed_tracks(ctx: MethodContext, base: Baseline) -> list[tuple]:
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
