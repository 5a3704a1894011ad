"""High-level planning API used by the CLI and the ROS node: voyage -> frozen `RoutePlan`.

`plan_voyage` resolves ports, splits a multi-port voyage into legs with their own time
windows, gathers seeds (seed pool, previous plan shifted to the ship's position), runs the
chosen method per leg within the wall-time budget, computes the constant-RPM baseline with the
same evaluator, stores the result in the seed pool and joins everything into one plan.
"""

from __future__ import annotations

import dataclasses
import itertools
import time
from collections.abc import Callable, Sequence
from datetime import UTC, datetime, timedelta
from pathlib import Path
from typing import Any

import numpy as np

from shiproute_planner.method_context import Progress
from shiproute_planner.methods import MethodContext, compute_baseline, get_method
from shiproute_planner.route.approach import (
    sail_approach,
)
from shiproute_planner.route.canals import route_canals, sail_canal
from shiproute_planner.route.given_approach import load_approaches

from .checks.parameters import require_number
from .coastal_passages import passage_rules, passages_note
from .depth_setup import depth_limits, with_depth_report
from .errors import InvalidVoyageError, PlanCancelledError
from .forecast_statement import forecast_statement, prepare_forecast
from .ga.loop import GAConfig
from .ga.pool import SeedPool
from .geo.depth import Bathymetry
from .geo.landmask import LandMask, default_land_mask
from .geo.ports import Port, resolve_port
from .geo.zones import Zones
from .objectives import Economics, objective_block, objective_terms
from .plan_assembly import assemble_plan
from .plan_checks import checked_plan, zone_limits
from .plan_seeds import leg_seeds, offer_to_pool
from .plan_setup import (
    TimeLike,
    cancel_fn,
    chosen_model,
    make_environment,
    route_limits,
    rta_warning_of,
    to_posix_s,
)
from .plan_timing import PlanClock
from .plan_types import RoutePlan
from .route.voyage_legs import leg_setup
from .straits import route_straits, sail_strait
from .voyage.legs import voyage_schedule
from .voyage.plan_calls import with_port_calls
from .voyage.port_calls import PortCall
from .voyage.schedule import plan_schedule
from .voyage.spans import budget_share, span_plan
from .voyage.stage_length import (
    OCEAN_STAGE_H,
    RTA_TOLERANCE_S,
    check_rta_tolerance_s,
    scaled_ga_config,
)
from .voyage_ship import loaded_ship, loading_block


def _calls_of(via: Sequence[str | Port], via_rta: Sequence[TimeLike | None],
              depart_s: float) -> list[PortCall | None]:
    """Port calls of `via` ports whose `via_rta` is a latest arrival (None: no fixed time)."""
    rtas = list(via_rta) + [None] * (len(via) - len(via_rta))
    out: list[PortCall | None] = []
    for p, t in zip(via, rtas, strict=False):
        name = p.name if isinstance(p, Port) else str(p)
        latest = None if t is None else to_posix_s(t)
        if latest is not None and latest <= depart_s:
            raise InvalidVoyageError(f"via {name}: RTA is not after the departure")
        out.append(PortCall(name, None, latest, 0.0))
    return out


def _departure(call: PortCall | None, arrival_s: float) -> float:
    """Departure from a port reached at `arrival_s`: berth after the window opens."""
    if call is None:
        return arrival_s
    start = max(arrival_s, call.earliest_s) if call.earliest_s is not None else arrival_s
    return start + call.berth_s


def _deadline(call: PortCall | None, rta_s: float | None) -> float:
    """Latest arrival at a leg's end port (the RTA at the destination; inf: none)."""
    limits = [t for t in (rta_s, call.latest_s if call is not None else None) if t is not None]
    return min(limits) if limits else float("inf")


def plan_voyage(
    origin: str | Port,
    destination: str | Port,
    depart: TimeLike,
    rta: TimeLike | timedelta,
    ship: Any,
    forecast: Any = None,
    *,
    via: Sequence[str | Port] = (),
    via_rta: Sequence[TimeLike | None] = (),
    objective: str = "fuel",
    method: str = "seed_ga",
    budget_s: float = 3.0,
    seed: int | np.random.Generator = 0,
    stage_hours: float | None = None,
    previous_plan: RoutePlan | None = None,
    position: tuple[float, float, float] | None = None,
    seed_pool_dir: str | Path | None = None,
    progress: Callable[[Progress], None] | None = None,
    cancel: Any = None,
    limits: dict | None = None,
    land: LandMask | None = None,
    ga_config: GAConfig | None = None,
    stall_generations: int = 0,
    max_generations: int = 100_000,
    max_evaluations: int = 0,
    with_baseline: bool = True,
    approach_nm: float = 25.0,
    approach_rpm: float | None = None,
    coastal_passage: bool = True,
    cycle_id: str = "",
    persistence_h: float = 24.0,
    climatology: Any = None,
    ship_model: str = "",
    bathymetry: Sequence[str | Path] | Bathymetry | None = None,
    default_bathymetry: bool = False,
    ukc_margin_m: float = 1.0,
    zones: Sequence[str | Path] | Zones | None = None,
    clearance_nm: float = 0.0,
    approaches_given: Sequence[str | Path] = (),
    loading: str = "",
    economics: Economics | None = None,
    port_calls: Sequence[PortCall] = (),
    rta_tolerance_s: float = RTA_TOLERANCE_S,
) -> RoutePlan:
    """Plan a voyage and return a frozen RoutePlan.

    `position` = (lat_deg, lon_deg, time POSIX s) of the ship for a re-plan under way: the
    voyage then starts there and `previous_plan` (shifted to it) seeds the GA. `cancel` is a
    callable returning True or an object with `is_set()` (threading.Event); a cancelled run
    returns the best plan so far. `budget_s` is the wall time of the whole call: each
    optimised span's search gets what set-up left, shared by genes (`voyage.spans`), and a
    plan over its budget says where the time went (`plan_timing`); with
    `max_generations` or `max_evaluations` (route evaluations of the whole voyage, shared
    between spans like the time; 0 = none) and an ample (or infinite) `budget_s` a run is
    reproducible for a given `seed`.
    The first and last `approach_nm` at each port follow the sea lane at `approach_rpm`
    (default: the calm-water RPM of the mean speed that meets the RTA), and with
    `coastal_passage` on through the straits and past the capes next to each port until the
    great circle between the approaches' ends is clear of land (each within the first/last
    sixth of the lane; off lets the method choose between straits); the method optimises
    between the approaches' sea ends. A forecast whose valid times miss the voyage is refused;
    beyond its ends its edge fields are held for `persistence_h`, then the monthly
    `climatology` (a canonical dataset whose times name the months) or calm water is assumed,
    and the plan states all of it (`forecast_statement`: warnings and `extra["forecast"]`).
    `ship_model` chooses the performance model
    (`learned.select.resolve_model`: physics, kwon, profile:FILE, learned:FILE; "" = the ship
    file's `performance_model` entry or physics); the choice is stated in the plan's warnings.
    `bathymetry` (grid files or a `Bathymetry`) plus, with
    `default_bathymetry` (on in the CLI, the node and `bench world`; off here so a library
    call uses no data it was not given), the packaged ETOPO5 grid make the under-keel
    clearance (margin `ukc_margin_m` on top of draft, squat and wave allowance) a constraint
    of every leg;
    `zones` (GeoJSON files or `Zones`) add no-go areas (hard) and avoid-if-possible areas
    (a penalty per NM). The finished plan gets the route check (land, `clearance_nm` from
    land, depth, zones) and carries its findings in its warnings. `approaches_given`: route
    files (RTZ/GeoJSON) of coastal passages from a port or to one, used as given.
    `loading`: the loading condition (a condition of the ship file, or drafts 'T_F,T_A' in
    m; '' = the file's default). `objective` co2 / cost take the fuel type and prices from
    `economics`, else the ship file, else stated defaults (`objectives`).
    `stage_hours` None derives each user's leg's stage from its window and sea lane
    (`voyage.stage_length`), one length for all its spans between straits and canals.
    `port_calls` (or `via` with `via_rta` as latest arrivals) make a multi-port voyage whose
    leg times are scheduled together for the least fuel (`voyage.schedule`); a plan is on
    time when it arrives within `rta_tolerance_s` of each deadline.
    """
    clock = PlanClock()
    if stage_hours is not None:
        require_number("stage_hours", stage_hours)
    rta_tolerance_s = check_rta_tolerance_s(rta_tolerance_s)
    if port_calls:
        via = [c.port for c in port_calls]
    land = land or default_land_mask()
    ship, model_notes = chosen_model(loaded_ship(ship, loading), ship_model)
    env, spec = make_environment(ship, forecast)
    terms = objective_terms(objective, dict(getattr(spec, "economics", ()) or ()), economics)
    if cycle_id:
        env = dataclasses.replace(env, cycle_id=cycle_id)
    lim = route_limits(spec, limits)
    lim, warnings = depth_limits(lim, spec, bathymetry, default_bathymetry, ukc_margin_m)
    lim, zone_notes = zone_limits(lim, zones)
    warnings += zone_notes
    given = load_approaches(approaches_given)
    ports = [p if isinstance(p, Port) else resolve_port(p, land)
             for p in (origin, *via, destination)]
    warnings += [p.note for p in ports if p.note]
    depart_s = to_posix_s(depart)
    rta_s = depart_s + rta.total_seconds() if isinstance(rta, timedelta) else to_posix_s(rta)
    if position is not None:
        lat, lon, now_s = position
        if land.is_land(np.array([lon]), np.array([lat]))[0]:
            raise InvalidVoyageError(f"ship position {lat:.4f},{lon:.4f} is on land")
        ports[0] = Port("ship position", "", float(lat), float(lon))
        depart_s = float(now_s)
    if not rta_s > depart_s:
        raise InvalidVoyageError("the RTA must be after the departure time")
    calls = list(port_calls) or _calls_of(via, via_rta, depart_s)
    user_ports = list(ports)  # the user's ports: stage length and budget follow their legs
    ports, canal_legs, calls_x, canal_notes = route_canals(ports, spec, calls)
    warnings += canal_notes
    strait_legs: dict = {}
    if coastal_passage:
        ports, canal_legs, strait_legs, calls_x, _ = route_straits(ports, canal_legs, calls_x)
        warnings.append(passages_note(passage_rules(lim.under_keel)))
    sched = None
    if len(ports) > 2:
        call_at = {k + 1: c for k, c in enumerate(calls_x) if c is not None}
        sched_legs, sched, notes, rate = voyage_schedule(
            ports, call_at, canal_legs, depart_s, rta_s, env.model, lim.rpm_min, lim.rpm_max)
        warnings += notes
        leg_rtas = [*sched.arrival_s[:-1], rta_s]  # the last leg aims at the RTA itself
    else:
        call_at, leg_rtas = {}, [rta_s]
    env = dataclasses.replace(env, sampler=prepare_forecast(env.sampler, depart_s, rta_s,
                                                            persistence_h, climatology))
    rta_warning, earliest_s = rta_warning_of(ports, depart_s, rta_s, spec)
    # an RTA beyond reach is searched best effort: over the time the great circle takes at
    # full speed (a lower bound), lateness being a violation the search minimises; a
    # schedule (ports, canals, straits) never asks a leg for more than the ship can do
    search_rtas = [*leg_rtas[:-1], earliest_s] if rta_warning else list(leg_rtas)
    spans = span_plan(user_ports, ports, set(canal_legs) | set(strait_legs), search_rtas,
                      depart_s, stage_hours)
    is_cancelled = cancel_fn(cancel)
    rng = seed if isinstance(seed, np.random.Generator) else np.random.default_rng(seed)
    pool = SeedPool(seed_pool_dir) if seed_pool_dir is not None else None
    month = datetime.fromtimestamp(depart_s, UTC).month
    fn = get_method(method)
    clock.lap("set-up")
    results, baselines, problems, sources, approaches = [], [], [], [], []
    arrivals: list[float] = []
    gens = evals = 0
    leg_depart = depart_s
    for k, (a, b) in enumerate(itertools.pairwise(ports)):
        if k in canal_legs:  # a fixed passage: sailed along the canal at its transit speed
            canal, rev = canal_legs[k]
            sea_rpm = float(results[-1].legs["rpm"][0, -1]) if results else None
            lead_in, ev, lead_out, rpm_c, canal_problem = sail_canal(
                env, canal, rev, leg_depart, lim, (stage_hours or OCEAN_STAGE_H) * 3600.0,
                sea_rpm)
            clock.lap("passages")
            results.append(ev)
            sources.append("canal")
            problems.append(canal_problem)
            if with_baseline:
                baselines.append(("canal", rpm_c, ev))
            approaches.append((lead_in, lead_out))
            leg_depart = float((lead_out or ev).eta_s[0])
            arrivals.append(leg_depart)
            leg_depart = _departure(call_at.get(k + 1), leg_depart)
            continue
        if k in strait_legs:  # a computed passage between the strait's gates, at sea RPM
            ev, rpm_s, strait_problem, said = sail_strait(
                env, strait_legs[k], leg_depart, lim, (stage_hours or OCEAN_STAGE_H) * 3600.0,
                float(results[-1].legs["rpm"][0, -1]) if results else None)
            clock.lap("passages")
            warnings += said
            results.append(ev)
            sources.append("strait")
            problems.append(strait_problem)
            if with_baseline:
                baselines.append(("strait", rpm_s, ev))
            approaches.append((None, None))
            leg_depart = float(ev.eta_s[0])
            arrivals.append(leg_depart)
            leg_depart = _departure(call_at.get(k + 1), leg_depart)
            continue
        under_way = k == 0 and position is not None
        if sched is not None and 0 < k < len(ports) - 2 and not rta_warning:
            # closed loop: the legs left re-scheduled from where and when this one starts
            search_rtas[k] = plan_schedule(sched_legs[k:], leg_depart, rta_s, rate).arrival_s[0]
        leg_rta = max(search_rtas[k], leg_depart + 60.0)
        leg = leg_setup(a, b, env, lim, land, leg_depart, leg_rta, approach_nm=approach_nm,
                        approach_rpm=approach_rpm, coastal_passage=coastal_passage,
                        stage_hours=spans.stage_hours[k], objective=objective, terms=terms,
                        under_way=under_way, previous_plan=previous_plan if under_way else None,
                        position=position if under_way else None, given=given,
                        target_stages=spans.target_stages[k])
        problem, pre, ap_arr, rpm_ap = leg.problem, leg.pre, leg.ap_arr, leg.rpm_ap
        warnings += [n for n in leg.notes if n not in warnings]
        seeds, gene_seeds = leg_seeds(problem, pool, a, b, month,
                                   previous_plan if k == 0 else None, position)
        clock.lap("passages")
        need = with_baseline or (method == "seed_ga" and not seeds)
        base = compute_baseline(problem, env, land) if need else None
        clock.lap("baselines")
        share = budget_share(spans, k, problem.n_var, search_rtas)
        leg_budget = max(clock.left_s(budget_s) * share, 0.0)
        leg_evals = max(round((max_evaluations - evals) * share), 1) if max_evaluations else 0
        ctx = MethodContext(problem, env, land, rng, leg_budget, seeds, progress, is_cancelled,
                            k, time.perf_counter(), scaled_ga_config(ga_config, problem.n_stages),
                            stall_generations=stall_generations,
                            baseline=base, max_generations=max_generations,
                            gene_seeds=gene_seeds, max_evaluations=leg_evals)
        res = fn(ctx)
        clock.lap("search")
        if res.evaluation is None:
            raise PlanCancelledError("planning was cancelled before a route was found")
        results.append(res.evaluation)
        sources.append(res.seed_source)
        problems.append(problem)
        gens += res.generations
        evals += res.evaluations
        if with_baseline and base is not None:
            baselines.append((base.name, base.rpm, base.evaluation))
        if pool is not None:
            offer_to_pool(pool, problem, a, b, month, res.evaluation, res.seed_source, res.genes)
        leg_depart = float(res.evaluation.eta_s[0])
        post = sail_approach(env, ap_arr, rpm_ap, leg_depart, lim) if ap_arr else None
        if post is not None:
            leg_depart = float(post.eta_s[0])
        approaches.append((pre, post))
        arrivals.append(leg_depart)
        leg_depart = _departure(call_at.get(k + 1), leg_depart)
        clock.lap("passages")
    land.fine_coast.save()  # coastal cells this plan resolved: later processes start with them
    deadlines = [_deadline(call_at.get(k + 1), rta_s if k == len(results) - 1 else None)
                 + rta_tolerance_s for k in range(len(results))]
    plan = assemble_plan(ports, problems, results, baselines, sources, approaches, env, spec,
                     method, objective, depart_s, rta_s, leg_rtas, gens, evals,
                     clock.elapsed_s(), deadlines)
    if sched is not None:
        plan = with_port_calls(plan, sched_legs, sched, arrivals, ports, rta_tolerance_s)
    if model_notes:
        from .learned.select import plan_warnings

        notes = model_notes + plan_warnings(env.model, plan)
        plan = dataclasses.replace(plan, warnings=plan.warnings + notes)
    if rta_warning:
        plan = dataclasses.replace(plan, warnings=(*plan.warnings, rta_warning))
    plan = checked_plan(with_depth_report(plan, lim.under_keel, warnings), land, lim,
                        clearance_nm)
    block, said = forecast_statement(env.sampler, plan, persistence_h)
    goal = objective_block(terms, plan.total_fuel_t, plan.total_time_s / 3600.0,
                           plan.total_distance_nm)
    clock.lap("checks")
    late = clock.overrun_warning(budget_s)
    return dataclasses.replace(plan, warnings=(*plan.warnings, *said, *terms.notes,
                                               *([late] if late else [])),
                               extra={**plan.extra, "forecast": block, "objective": goal,
                                      "timing_s": clock.block(budget_s),
                                      **loading_block(spec)})
