"""A prepared voyage sailed leg by leg: canals and straits on their fixed passages, every
other leg optimised by the chosen method within its share of the budget, each leg starting
when the one before it ends (after the port call's window and berth time)."""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field
from datetime import UTC, datetime

import numpy as np

from .ensemble_report import MemberLeg
from .errors import PlanCancelledError
from .ga.pool import SeedPool
from .geo.fine_distance import default_fine_distance
from .geo.landmask import LandMask
from .method_context import MethodContext, MethodFn, baseline_track, compute_baseline
from .methods import get_method
from .plan_prepare import PreparedVoyage
from .plan_repair import (
    RepairContext,
    is_berth,
    repair_context,
    repaired_canal,
    repaired_leg,
)
from .plan_seeds import leg_seeds, offer_to_pool
from .plan_setup import cancel_fn
from .plan_timing import PlanClock
from .request import PlanOptions, VoyageRequest
from .route.approach import sail_approach
from .route.canals import sail_canal
from .route.clearance import NARROWS_REACH_NM
from .route.evaluation import RouteEvaluation
from .route.given_approach import approaches_at
from .route.lane_narrows import lane_narrows, narrows_statement, with_narrows
from .route.problem import RouteProblem
from .route.seed_repair import repair_builds
from .route.voyage_legs import leg_setup
from .ship import SeaState
from .ship.errors import ShipModelError
from .straits import sail_strait
from .voyage.port_calls import PortCall
from .voyage.schedule import plan_schedule
from .voyage.spans import budget_share
from .voyage.stage_length import OCEAN_STAGE_H, scaled_ga_config

Leg = RouteEvaluation | None  # an approach or lead-in/out sailed, or none


def departure_after(call: PortCall | None, arrival_s: float) -> float:
    """Departure from a port reached at `arrival_s`: berth after the window opens."""
    if call is None:
        return arrival_s
    start = max(arrival_s, call.earliest_s) if call.earliest_s is not None else arrival_s
    return start + call.berth_s


@dataclass
class LegRun:
    """The legs planned so far (grows as the voyage is sailed)."""

    depart_s: float  # when the next leg starts
    search_rtas: list[float]
    warnings: list[str]
    results: list[RouteEvaluation] = field(default_factory=list)  # one row per leg
    baselines: list[tuple[str, float, RouteEvaluation]] = field(default_factory=list)
    problems: list[RouteProblem] = field(default_factory=list)
    sources: list[str] = field(default_factory=list)
    approaches: list[tuple[Leg, Leg]] = field(default_factory=list)  # (in, out) of a leg
    arrivals: list[float] = field(default_factory=list)
    member_legs: list[MemberLeg] = field(default_factory=list)  # optimised legs (ensembles)
    generations: int = 0
    evaluations: int = 0
    repairs: list[dict] = field(default_factory=list)  # land repairs (`plan_repair`)

    def sea_rpm(self) -> float | None:
        """RPM at the end of the last leg (a fixed passage goes on at it)."""
        return float(self.results[-1].legs["rpm"][0, -1]) if self.results else None

    def add(self, evaluation: RouteEvaluation, source: str, problem: RouteProblem,
            approaches: tuple[Leg, Leg],
            baseline: tuple[str, float, RouteEvaluation] | None) -> None:
        """Record one leg's route (and its baseline, when one is kept)."""
        self.results.append(evaluation)
        self.sources.append(source)
        self.problems.append(problem)
        self.approaches.append(approaches)
        if baseline is not None:
            self.baselines.append(baseline)

    def take_repairs(self, rows: list[dict]) -> None:
        """Land repairs of a leg: rows for the plan's JSON, their words in its warnings."""
        self.repairs += rows
        self.warnings += [r["text"] for r in rows]

    def arrive(self, arrival_s: float, call: PortCall | None) -> None:
        """The leg ends at `arrival_s`; the next one leaves after the port call."""
        self.arrivals.append(arrival_s)
        self.depart_s = departure_after(call, arrival_s)


@dataclass(frozen=True)
class Search:
    """The voyage-wide search state every optimised leg shares."""

    method: MethodFn
    rng: np.random.Generator
    pool: SeedPool | None
    month: int
    cancelled: Callable[[], bool]
    clock: PlanClock  # the plan's wall clock, lapped per phase
    repair: RepairContext  # the final land check and repair of every leg


def search_of(prep: PreparedVoyage, options: PlanOptions, clock: PlanClock,
              clearance_nm: float | None = None) -> Search:
    """The method, random generator, seed pool, clock and land repair of a plan."""
    seed = options.seed
    rng = seed if isinstance(seed, np.random.Generator) else np.random.default_rng(seed)
    pool = SeedPool(options.seed_pool_dir) if options.seed_pool_dir is not None else None
    month = datetime.fromtimestamp(prep.depart_s, UTC).month
    return Search(get_method(options.method), rng, pool, month, cancel_fn(options.cancel),
                  clock, repair_context(prep.env, prep.limits, clearance_nm))


def sail_canal_leg(prep: PreparedVoyage, run: LegRun, k: int, options: PlanOptions,
                   repair: RepairContext) -> None:
    """A canal: sailed along its line at its transit speed (lead-in and lead-out checked
    at the final coastline and repaired like every leg)."""
    canal, rev = prep.canal_legs[k]
    lead_in, ev, lead_out, rpm_c, problem = sail_canal(
        prep.env, canal, rev, run.depart_s, prep.limits,
        (options.stage_hours or OCEAN_STAGE_H) * 3600.0, run.sea_rpm())
    lead_in, ev, lead_out, fixed = repaired_canal(repair, canal.name, lead_in, ev, lead_out,
                                                  problem)
    run.take_repairs(fixed)
    run.add(ev, "canal", problem, (lead_in, lead_out),
            ("canal", rpm_c, ev) if options.with_baseline else None)
    run.arrive(float((lead_out or ev).eta_s[0]), prep.call_at.get(k + 1))


def sail_strait_leg(prep: PreparedVoyage, run: LegRun, k: int, options: PlanOptions,
                    repair: RepairContext) -> None:
    """A strait: the computed passage between its gates, at the schedule's RPM (checked at
    the final coastline and repaired like every leg)."""
    ev, rpm_s, problem, said = sail_strait(
        prep.env, prep.strait_legs[k], run.depart_s, prep.limits,
        (options.stage_hours or OCEAN_STAGE_H) * 3600.0, scheduled_rpm(prep, run, k))
    _, ev, _, fixed = repaired_leg(repair, (prep.ports[k], prep.ports[k + 1]),
                                   berths_of(prep, k), None, ev, problem, None)
    run.warnings += said
    run.take_repairs(fixed)
    run.add(ev, "strait", problem, (None, None),
            ("strait", rpm_s, ev) if options.with_baseline else None)
    run.arrive(float(ev.eta_s[0]), prep.call_at.get(k + 1))


def leg_target_s(prep: PreparedVoyage, run: LegRun, k: int) -> float:
    """What leg `k` aims at; between port calls the legs left are re-scheduled from where
    and when this one starts (closed loop)."""
    if (prep.schedule is not None and prep.fuel_rate is not None
            and 0 < k < len(prep.ports) - 2 and not prep.rta_warning):
        run.search_rtas[k] = plan_schedule(prep.schedule_legs[k:], run.depart_s, prep.rta_s,
                                           prep.fuel_rate).arrival_s[0]
    return max(run.search_rtas[k], run.depart_s + 60.0)


def scheduled_rpm(prep: PreparedVoyage, run: LegRun, k: int) -> float | None:
    """Calm-water RPM that sails fixed leg `k` (a strait or shoal passage) in the time the
    schedule, re-planned from now, gives it; without a schedule or a model that inverts
    speed, the RPM the last leg ended at. That RPM would pass a short leg's pace on (a
    span of 60 NM sailed at the slowest RPM sent the Rio de la Plata passage on at it)."""
    model = prep.env.model
    if (prep.schedule is None or prep.fuel_rate is None or prep.rta_warning
            or not hasattr(model, "rpm_for_speed")):
        return run.sea_rpm()
    sail_s = leg_target_s(prep, run, k) - run.depart_s
    speed = prep.schedule_legs[k].distance_m / max(sail_s, 3600.0)
    try:
        return float(model.rpm_for_speed(np.array([speed]), np.array([0.0]),
                                         SeaState.calm(1))[0])
    except (ValueError, ArithmeticError, ShipModelError):
        return run.sea_rpm()


def leg_budget(prep: PreparedVoyage, options: PlanOptions, search: Search, run: LegRun,
               k: int, genes_k: int) -> tuple[float, int]:
    """(wall time [s], route evaluations) of span `k` with `genes_k` genes: its share by
    genes (`voyage.spans`) of what set-up and the spans before it left of the budget."""
    assert prep.spans is not None
    share = budget_share(prep.spans, k, genes_k, run.search_rtas)
    wall_s = max(search.clock.left_s(options.budget_s) * share, 0.0)
    total = options.max_evaluations
    evals = max(round((total - run.evaluations) * share), 1) if total else 0
    return wall_s, evals


def plan_leg(prep: PreparedVoyage, run: LegRun, k: int, request: VoyageRequest,
             options: PlanOptions, search: Search) -> None:
    """An open-sea leg a -> b: approaches, then the method between their sea ends."""
    a, b = prep.ports[k], prep.ports[k + 1]
    under_way = k == 0 and options.position is not None
    spans = prep.spans
    assert spans is not None  # prepare_voyage always plans the spans
    leg = leg_setup(a, b, prep.env, prep.limits, prep.land, run.depart_s,
                    leg_target_s(prep, run, k), approach_nm=request.approach_nm,
                    approach_rpm=request.approach_rpm, coastal_passage=request.coastal_passage,
                    stage_hours=spans.stage_hours[k], objective=request.objective,
                    terms=prep.terms, under_way=under_way,
                    previous_plan=options.previous_plan if under_way else None,
                    position=options.position if under_way else None, given=prep.given,
                    target_stages=spans.target_stages[k])
    problem = leg.problem
    run.warnings += [n for n in leg.notes if n not in run.warnings]
    seeds, gene_seeds = leg_seeds(problem, search.pool, a, b, search.month,
                                  options.previous_plan, under_way)
    search.clock.lap("passages")
    need = options.with_baseline or (options.method == "seed_ga" and not seeds)
    repairs0, seconds0 = repair_builds()
    kept = (options.previous_plan.extra.get("lane_narrows")
            if under_way and options.previous_plan is not None else None)
    inherited = None if kept is None else tuple((float(p[0]), float(p[1])) for p in kept)
    problem = leg_narrows(problem, prep.land, inherited)
    narrows = problem.limits.clearance.narrows
    if narrows and inherited is None:
        rule = problem.limits.clearance
        run.warnings.append(narrows_statement(narrows, a.name, b.name, rule.open_sea_nm,
                                              rule.approach_nm, NARROWS_REACH_NM))
    base = compute_baseline(problem, prep.env, prep.land) if need else None
    repairs, seconds = repair_builds()
    if repairs > repairs0:  # the lane repaired afresh: one-off work, not the search's time
        search.clock.excuse(seconds - seconds0)
        run.warnings.append(repair_statement(seconds - seconds0, a.name, b.name))
    search.clock.lap("baselines")
    wall_s, evals = leg_budget(prep, options, search, run, k, problem.n_var)
    ctx = MethodContext(problem, prep.env, prep.land, search.rng, wall_s, seeds,
                        options.progress, search.cancelled, k, time.perf_counter(),
                        scaled_ga_config(options.ga_config, problem.n_stages),
                        stall_generations=options.stall_generations, baseline=base,
                        max_generations=options.max_generations, gene_seeds=gene_seeds,
                        max_evaluations=evals)
    res = search.method(ctx)
    search.clock.lap("search")
    if res.evaluation is None:
        raise PlanCancelledError("planning was cancelled before a route was found")
    run.warnings += [n for n in res.notes if n not in run.warnings]
    run.member_legs.append(MemberLeg(problem, res.genes, res.evaluation))
    run.generations += res.generations
    run.evaluations += res.evaluations
    if search.pool is not None:
        offer_to_pool(search.pool, problem, a, b, search.month, res.evaluation,
                      res.seed_source, res.genes)
    ap_arr, rpm_ap = leg.ap_arr, leg.rpm_ap
    mine_dep, mine_arr = approaches_at(prep.given, a, b)
    pre, span, post, fixed = repaired_leg(
        search.repair, (a, b), berths_of(prep, k), leg.pre, res.evaluation, problem,
        (lambda t: sail_approach(prep.env, ap_arr, rpm_ap, t, prep.limits)) if ap_arr else None,
        (mine_dep is not None and not under_way, mine_arr is not None))
    run.take_repairs(fixed)
    end_s = float(span.eta_s[0])
    kept = (base.name, base.rpm, base.evaluation) if options.with_baseline and base else None
    run.add(span, res.seed_source, problem, (pre, post), kept)
    run.arrive(float(post.eta_s[0]) if post is not None else end_s, prep.call_at.get(k + 1))
    search.clock.lap("passages")


def leg_narrows(problem: RouteProblem, land: LandMask,
                inherited: tuple[tuple[float, float], ...] | None) -> RouteProblem:
    """The leg's problem with the narrows its repaired sea lane passes (`route.lane_narrows`;
    none when the great circle stays off land); a re-plan under way keeps the previous
    plan's (`inherited`) instead of repairing the lane from the ship's position."""
    if inherited is not None:
        return with_narrows(problem, inherited)
    name, lon, lat = baseline_track(problem, land)
    return with_narrows(problem, lane_narrows(problem, lon, lat)) if name == "sea_lane" else problem


def repair_statement(seconds: float, a: str, b: str) -> str:
    """The plan's word when the baseline's sea lane a -> b was repaired at full resolution
    rather than read back (`route.seed_repair`), time the plan clock excuses from the search."""
    return (f"baseline: the sea lane {a} -> {b} repaired at full resolution in {seconds:.2f} s "
            f"(a lane first met on this machine, kept for later plans); the search's clock "
            f"was extended by as much")


def berths_of(prep: PreparedVoyage, k: int) -> tuple[bool, bool]:
    """Whether leg `k` starts and ends at a berth (land round it is the pilot's)."""
    n = len(prep.ports)
    return is_berth(prep.ports[k], k, n), is_berth(prep.ports[k + 1], k + 1, n)


def sail_legs(request: VoyageRequest, options: PlanOptions, prep: PreparedVoyage,
              clock: PlanClock) -> LegRun:
    """Every leg of the prepared voyage, in order."""
    search = search_of(prep, options, clock, request.clearance_nm)
    run = LegRun(prep.depart_s, list(prep.search_rtas), list(prep.warnings))
    for k in range(len(prep.ports) - 1):
        if k in prep.canal_legs:
            sail_canal_leg(prep, run, k, options, search.repair)
            clock.lap("passages")
        elif k in prep.strait_legs:
            sail_strait_leg(prep, run, k, options, search.repair)
            clock.lap("passages")
        else:
            plan_leg(prep, run, k, request, options, search)
    # level-1 tiles and intermediate coastal cells this plan resolved: later processes use them
    default_fine_distance().save()
    prep.land.fine_coast.save()
    return run

