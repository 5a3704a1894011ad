"""High-level planning API used by the CLI and the ROS node: voyage -> frozen `RoutePlan`.

`plan_voyage` resolves ports, splits a multi-port voyage into legs with their own time
windows, gathers seeds (seed pool, previous plan shifted to the ship's position), runs the
chosen method per leg within the wall-time budget, computes the constant-RPM baseline with the
same evaluator, stores the result in the seed pool and joins everything into one plan.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
import time
import uuid
from collections.abc import Callable, Sequence
from datetime import UTC, datetime, timedelta
from pathlib import Path
from typing import Any

import numpy as np
from shiproute_core.geodesy import inverse, unwrap_near

from .approach import Approach, CoastalPassage, approach_length_m, lane_approaches, sail_approach
from .canals import route_canals, sail_canal
from .checks.parameters import require_number
from .coastal_passages import computed_approach, passage_rules, passages_note
from .depth_setup import depth_limits, with_depth_report
from .errors import InvalidVoyageError, PlanCancelledError
from .forecast_statement import forecast_statement, prepare_forecast
from .ga.loop import GAConfig
from .ga.pool import Seed, SeedPool, pool_key
from .ga.seeds import TrackSeed, shift_track
from .geo.depth import Bathymetry
from .geo.landmask import LandMask, default_land_mask
from .geo.ports import Port, resolve_port
from .geo.zones import Zones
from .given_approach import approaches_at, load_approaches
from .methods import MethodContext, Progress, compute_baseline, get_method
from .objective_window import search_window_s
from .objectives import Economics, ObjectiveTerms, objective_block, objective_terms
from .plan_checks import checked_plan, zone_limits
from .plan_types import RoutePlan, Waypoint, reasons_of, waypoints_from_evaluation
from .route.environment import Environment
from .route.evaluation import RouteEvaluation
from .route.problem import RouteLimits, RouteProblem
from .straits import is_gate, route_straits, sail_strait
from .voyage.legs import sea_distance_m, turns_to_round, voyage_schedule
from .voyage.plan_calls import with_port_calls
from .voyage.port_calls import PortCall
from .voyage.schedule import plan_schedule
from .voyage.stage_length import (
    OCEAN_STAGE_H,
    RTA_TOLERANCE_S,
    check_rta_tolerance_s,
    leg_stage_hours,
    scaled_ga_config,
)
from .voyage_ship import loaded_ship, loading_block

TimeLike = datetime | float | int | str


def to_posix_s(value: TimeLike) -> float:
    """UTC datetime, ISO 8601 string ('Z' allowed) or POSIX seconds -> POSIX seconds."""
    if isinstance(value, int | float):
        return float(value)
    if isinstance(value, str):
        value = datetime.fromisoformat(value.strip().replace("Z", "+00:00"))
    if value.tzinfo is None:
        value = value.replace(tzinfo=UTC)
    return value.timestamp()


def load_forecast(name_or_path: str | Sequence[str], waves_from_wind: bool = True) -> Any:
    """Canonical forecast dataset from file paths (one cycle: wind, waves and currents may
    come from different files) or a bundled scenario name. A file that cannot be used is
    refused with InvalidVoyageError naming it and the reason."""
    from shiproute_weather.errors import WeatherError
    from shiproute_weather.scenarios.catalogue import scenario_dataset, scenario_names

    names = [name_or_path] if isinstance(name_or_path, str | Path) else list(name_or_path)
    if len(names) == 1 and not Path(names[0]).exists() and names[0] in scenario_names():
        return scenario_dataset(str(names[0]))
    for n in names:
        if not Path(n).exists():
            raise InvalidVoyageError(
                f"forecast {str(n)!r} is neither a file nor a bundled scenario "
                f"({', '.join(scenario_names())})")
    from shiproute_weather.ingest.loaders import open_forecast

    try:
        return open_forecast([str(n) for n in names], waves_from_wind=waves_from_wind)
    except WeatherError as exc:
        raise InvalidVoyageError(f"forecast refused: {exc}") from exc


def make_environment(ship: Any, forecast: Any = None) -> tuple[Environment, Any]:
    """Environment from a ship (name, path, ShipSpec or model) and forecast (Dataset, sampler
    or None for calm water). Returns (environment, ShipSpec or None)."""
    from .ship import ShipSpec, load_ship

    spec = None
    if isinstance(ship, str | Path):
        spec = load_ship(ship)
    elif isinstance(ship, ShipSpec):
        spec = ship
    model = ship if spec is None else _fast_model(spec)
    if spec is None:
        spec = getattr(model, "ship", None) or getattr(model, "spec", None)
    sampler, cycle = None, ""
    if forecast is not None:
        if hasattr(forecast, "sample"):
            sampler = forecast
            cycle = str(getattr(forecast, "cycle_id", "") or "")
        else:
            from shiproute_weather.sampling.sampler import ForecastSampler

            sampler = ForecastSampler(forecast)
            cycle = str(forecast.attrs.get("cycle_id", ""))
    return Environment(model, sampler, cycle), spec


def _fast_model(spec: Any) -> Any:
    """The tabulated ship model (cached per ship and loading condition)."""
    from .ship.fast import fast_model

    return fast_model(spec)


def route_limits(spec: Any, overrides: dict | None = None) -> RouteLimits:
    """Route limits of a ship (engine RPM range, seakeeping criteria) with `overrides`."""
    kw: dict[str, Any] = {}
    if spec is not None:
        kw.update(rpm_min=spec.engine.rpm_min, rpm_max=spec.engine.rpm_max,
                  max_hs_m=spec.seakeeping.max_hs_m, max_wind_m_s=spec.seakeeping.max_wind_m_s,
                  p_slamming_max=spec.seakeeping.slamming_probability,
                  p_deck_wetness_max=spec.seakeeping.deck_wetness_probability,
                  p_propeller_emergence_max=spec.seakeeping.propeller_emergence_probability)
    kw.update(overrides or {})
    if "rpm_min" not in kw or "rpm_max" not in kw:
        raise InvalidVoyageError("RPM range unknown: give a ship file or limits rpm_min/rpm_max")
    return RouteLimits(**kw)


def _port_id(p: Port) -> str:
    return p.locode or f"{p.lat_deg:.2f},{p.lon_deg:.2f}"


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
    returns the best plan so far. `budget_s` is the wall time of the whole call (the search
    keeps at least half of it, so a cold process may overrun by the loading time); with
    `max_generations` or `max_evaluations` (route evaluations of the whole voyage, shared
    between legs by distance; 0 = none) and an ample (or infinite) `budget_s` a run is
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
    `stage_hours` None derives each leg's stage from its window (`voyage.stage_length`).
    `port_calls` (or `via` with `via_rta` as latest arrivals) make a multi-port voyage whose
    leg times are scheduled together for the least fuel (`voyage.schedule`); a plan is on
    time when it arrives within `rta_tolerance_s` of each deadline.
    """
    t0 = time.perf_counter()
    if stage_hours is not None:
        require_number("stage_hours", stage_hours)
    rta_tolerance_s = check_rta_tolerance_s(rta_tolerance_s)
    if port_calls:
        via = [c.port for c in port_calls]
    land = land or default_land_mask()
    ship, model_notes = _chosen_model(loaded_ship(ship, loading), ship_model)
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
    rta_warning, earliest_s = _rta_warning(ports, depart_s, rta_s, spec)
    # an RTA beyond reach is searched best effort: over the time the great circle takes at
    # full speed (a lower bound), lateness being a violation the search minimises; a
    # schedule (ports, canals, straits) never asks a leg for more than the ship can do
    search_rtas = [*leg_rtas[:-1], earliest_s] if rta_warning else list(leg_rtas)
    is_cancelled = _cancel_fn(cancel)
    rng = seed if isinstance(seed, np.random.Generator) else np.random.default_rng(seed)
    pool = SeedPool(seed_pool_dir) if seed_pool_dir is not None else None
    month = datetime.fromtimestamp(depart_s, UTC).month
    fn = get_method(method)
    dists = np.array([float(inverse(a.lon_deg, a.lat_deg, b.lon_deg, b.lat_deg)[1])
                      for a, b in itertools.pairwise(ports)])
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
                        stage_hours=stage_hours, objective=objective, terms=terms,
                        under_way=under_way, previous_plan=previous_plan if under_way else None,
                        position=position if under_way else None, given=given)
        problem, pre, ap_arr, rpm_ap = leg.problem, leg.pre, leg.ap_arr, leg.rpm_ap
        warnings += [n for n in leg.notes if n not in warnings]
        seeds, gene_seeds = _seeds(problem, pool, a, b, month,
                                   previous_plan if k == 0 else None, position)
        used = time.perf_counter() - t0
        share = dists[k] / dists[k:].sum()
        # the search keeps at least half its share even when a cold process spent the
        # budget on loading (sea-lane graph, coastline polygons, compiled kernels)
        leg_budget = max((budget_s - used) * share, 0.5 * budget_s * share, 0.0)
        leg_evals = max(round((max_evaluations - evals) * share), 1) if max_evaluations else 0
        need = with_baseline or (method == "seed_ga" and not seeds)
        base = compute_baseline(problem, env, land) if need else None
        ctx = MethodContext(problem, env, land, rng, leg_budget, seeds, progress, is_cancelled,
                            k, time.perf_counter(), scaled_ga_config(ga_config, problem.n_stages),
                            stall_generations=stall_generations,
                            baseline=base, max_generations=max_generations,
                            gene_seeds=gene_seeds, max_evaluations=leg_evals)
        res = fn(ctx)
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
            _offer(pool, problem, a, b, month, res.evaluation, res.seed_source, res.genes)
        leg_depart = float(res.evaluation.eta_s[0])
        post = sail_approach(env, ap_arr, rpm_ap, leg_depart, lim) if ap_arr else None
        if post is not None:
            leg_depart = float(post.eta_s[0])
        approaches.append((pre, post))
        arrivals.append(leg_depart)
        leg_depart = _departure(call_at.get(k + 1), leg_depart)
    land.fine_coast.save()  # coastal cells this plan resolved: later processes start with them
    deadlines = [_deadline(call_at.get(k + 1), rta_s if k == len(results) - 1 else None)
                 + rta_tolerance_s for k in range(len(results))]
    plan = _assemble(ports, problems, results, baselines, sources, approaches, env, spec,
                     method, objective, depart_s, rta_s, leg_rtas, gens, evals,
                     time.perf_counter() - t0, deadlines)
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
    return dataclasses.replace(plan, warnings=(*plan.warnings, *said, *terms.notes),
                               extra={**plan.extra, "forecast": block, "objective": goal,
                                      **loading_block(spec)})


def _chosen_model(ship: Any, ship_model: str) -> tuple[Any, tuple[str, ...]]:
    """(ship or performance model, notes for the plan's warnings) for a `ship_model` choice."""
    from .ship import ShipSpec, load_ship

    if not isinstance(ship, str | Path | ShipSpec):
        if ship_model:
            raise InvalidVoyageError("give ship_model with a ship name/file, not with a model")
        return ship, ()
    spec = ship if isinstance(ship, ShipSpec) else load_ship(ship)
    if (ship_model or spec.performance_model or "physics") == "physics":
        return spec, ()
    from .learned.select import resolve_model
    from .ship import ShipModelError

    try:
        return resolve_model(spec, ship_model)
    except ShipModelError as exc:  # wrong ship, unreadable model file, unknown choice
        raise InvalidVoyageError(f"ship model: {exc}") from exc



def _rta_warning(ports: list[Port], depart_s: float, rta_s: float,
                 spec: Any) -> tuple[str, float]:
    """Why the RTA cannot be met even on great circles at full calm-water speed ('' when it
    can, or without a ship file), and the arrival time at that speed [POSIX s]."""
    if spec is None:
        return "", rta_s
    from .checks.voyage import max_calm_speed_kn

    dist_nm = sum(float(inverse(a.lon_deg, a.lat_deg, b.lon_deg, b.lat_deg)[1])
                  for a, b in itertools.pairwise(ports)) / 1852.0
    need_kn = dist_nm / ((rta_s - depart_s) / 3600.0)
    top_kn = max_calm_speed_kn(spec)
    earliest_s = depart_s + dist_nm / top_kn * 3600.0
    if need_kn <= top_kn:
        return "", rta_s
    return (f"RTA unreachable: {dist_nm:.0f} NM (great circle, the shortest possible) in "
            f"{(rta_s - depart_s) / 3600:.1f} h needs {need_kn:.1f} kn, the ship makes at most "
            f"{top_kn:.1f} kn in calm water; best-effort plan (earliest arrival)"), earliest_s


@dataclasses.dataclass(frozen=True)
class LegSetup:
    """One leg as the methods see it: the problem between the approaches' sea ends, the
    sailed departure approach, the arrival approach and the approach RPM."""

    problem: RouteProblem
    pre: RouteEvaluation | None
    ap_arr: Approach | None
    rpm_ap: float
    notes: tuple[str, ...] = ()  # how the coastal passages were made (for the plan)


def leg_setup(a: Port, b: Port, env: Environment, lim: RouteLimits, land: LandMask,
              depart_s: float, rta_s: float, *, approach_nm: float = 25.0,
              approach_rpm: float | None = None, coastal_passage: bool = True,
              stage_hours: float | None = 12.0, objective: str = "fuel",
              terms: ObjectiveTerms | None = None, under_way: bool = False,
              previous_plan: RoutePlan | None = None,
              position: tuple[float, float, float] | None = None,
              given: Sequence[Approach] = ()) -> LegSetup:
    """Approaches of a leg a -> b and the problem between their sea ends (see `plan_voyage`;
    shared with the method comparison so every method solves the same problem). Under way
    the ship finishes the coastal passage it is in, if any, from where it is. `given`
    approaches (the user's coastal routes, e.g. from the ECDIS) that start at `a` or end at
    `b` replace the computed ones and are sailed as given."""
    coastal = CoastalPassage(land) if coastal_passage else None
    rest = _rest_of_approach(previous_plan, position) if under_way else None
    kept = _previous_arrival(previous_plan, b, position) if under_way else None
    if kept is not None:  # under way to the same port: the arrival approach stays as planned
        ap_dep, ap_arr = None, kept
    else:
        ap_dep, ap_arr = lane_approaches(
            a, b, approach_nm * 1852.0,
            with_dep=(not under_way or (coastal is not None and previous_plan is None))
            and not is_gate(a), with_arr=not is_gate(b),  # gates lie in open water
            coastal=coastal, dep_min_m=0.0 if under_way else None)
    notes: list[str] = []
    if coastal is not None and kept is None:  # computed on the fine grid, not the lane's cut
        rules = passage_rules(lim.under_keel)
        if rest is None:
            ap_dep, said = computed_approach(ap_dep, a.name, False, rules)
            notes += said
        ap_arr, said = computed_approach(ap_arr, b.name, True, rules)
        notes += said
    if rest is not None:
        ap_dep = rest
    mine_dep, mine_arr = approaches_at(given, a, b)
    if mine_dep is not None and not under_way:
        ap_dep = mine_dep
    if mine_arr is not None:
        ap_arr = mine_arr
    rpm_ap = approach_rpm or _lane_rpm(env, a, b, ap_dep, ap_arr, depart_s, rta_s, lim)
    pre = sail_approach(env, ap_dep, rpm_ap, depart_s, lim) if ap_dep else None
    t_leg = float(pre.eta_s[0]) if pre is not None else depart_s
    rta_leg = rta_s
    if ap_arr is not None:
        est = sail_approach(env, ap_arr, rpm_ap, rta_leg - 3600.0, lim)
        rta_leg -= float(est.eta_s[0] - est.time_s[0, 0])
    d_lon, d_lat = (ap_dep.lon_deg[-1], ap_dep.lat_deg[-1]) if ap_dep else (a.lon_deg, a.lat_deg)
    a_lon, a_lat = (ap_arr.lon_deg[0], ap_arr.lat_deg[0]) if ap_arr else (b.lon_deg, b.lat_deg)
    rta_leg = max(rta_leg, t_leg + 60.0)
    stage_h = stage_hours or leg_stage_hours(
        rta_leg - t_leg, turns_to_round(land, float(d_lon), float(d_lat), float(a_lon),
                                        float(a_lat)))
    span_s = search_window_s(terms, env.model,
                             float(inverse(d_lon, d_lat, a_lon, a_lat)[1]), rta_leg - t_leg)
    n_stages = (max(1, math.ceil(span_s / (stage_h * 3600.0)) - 1)
                if span_s < rta_leg - t_leg else 0)  # 0: the whole window
    problem = RouteProblem(float(d_lon), float(d_lat), float(a_lon), float(a_lat), t_leg,
                           rta_leg, lim, stage_s=stage_h * 3600.0, n_stages=n_stages,
                           objective=objective,
                           objective_per_t_fuel=terms.per_t_fuel if terms else 1.0,
                           objective_per_h=terms.per_h if terms else 0.0,
                           dep_name=a.name, arr_name=b.name)
    return LegSetup(problem, pre, ap_arr, float(rpm_ap), tuple(notes))


def _rest_of_approach(previous: RoutePlan | None,
                      position: tuple[float, float, float] | None) -> Approach | None:
    """What is left of the previous plan's departure approach from the ship's position (lat,
    lon, time), or None when the ship is past it (or there is no previous plan)."""
    if previous is None or position is None or not previous.optimised_spans:
        return None
    lon, lat, t = previous.track()
    start = previous.optimised_spans[0][0]
    now = position[2]
    if start == 0 or now >= t[start]:
        return None
    ahead = np.flatnonzero((t > now) & (np.arange(t.size) <= start))
    p_lon = unwrap_near(position[1], float(lon[ahead[0]])) if ahead.size else position[1]
    return Approach(np.concatenate([[p_lon], lon[ahead]]),
                    np.concatenate([[position[0]], lat[ahead]]))


def _previous_arrival(previous: RoutePlan | None, port: Port,
                      position: tuple[float, float, float] | None) -> Approach | None:
    """The previous plan's arrival approach when it ends at `port` and the ship (lat, lon,
    time) has not reached it yet: re-plans under way keep it instead of searching the sea lane
    and the coastal passage again from every new position (~0.2 s each)."""
    if previous is None or position is None or not previous.optimised_spans:
        return None
    lon, lat, t = previous.track()
    end = previous.optimised_spans[-1][1]
    if end >= lon.size - 1 or position[2] >= t[end]:
        return None
    if abs(lat[-1] - port.lat_deg) > 1e-6 or abs(unwrap_near(port.lon_deg, lon[-1])
                                                   - lon[-1]) > 1e-6:
        return None
    return Approach(lon[end:].copy(), lat[end:].copy())


def _lane_rpm(env: Environment, a: Port, b: Port, ap_dep, ap_arr, depart_s: float,
              rta_s: float, lim: RouteLimits) -> float:
    """Approach RPM: calm water RPM of the mean speed that meets the RTA on the approaches
    plus the sea lane between their sea ends, within the engine range."""
    ends = [(a.lon_deg, a.lat_deg), (b.lon_deg, b.lat_deg)]
    if ap_dep is not None:
        ends[0] = (ap_dep.lon_deg[-1], ap_dep.lat_deg[-1])
    if ap_arr is not None:
        ends[1] = (ap_arr.lon_deg[0], ap_arr.lat_deg[0])
    # the sea lane between the approaches' ends (round the land the great circle crosses)
    length = (approach_length_m(ap_dep) + approach_length_m(ap_arr)
              + sea_distance_m(*(round(float(v), 4) for v in (*ends[0], *ends[1]))))
    speed = length / max(rta_s - depart_s, 3600.0)
    model = env.model
    if hasattr(model, "rpm_for_speed"):
        from .ship import SeaState
        from .ship.errors import ShipModelError

        try:
            rpm = float(model.rpm_for_speed(np.array([min(speed, 30.0)]), np.array([0.0]),
                                            SeaState.calm(1))[0])
            return float(np.clip(rpm, lim.rpm_min, lim.rpm_max))
        except (ValueError, ArithmeticError, ShipModelError):
            # outside the model's range: an RTA beyond reach is sailed at full RPM
            return lim.rpm_max if speed > 10.0 else 0.5 * (lim.rpm_min + lim.rpm_max)
    return 0.5 * (lim.rpm_min + lim.rpm_max)


def _cancel_fn(cancel: Any) -> Callable[[], bool]:
    if cancel is None:
        return lambda: False
    if hasattr(cancel, "is_set"):
        return cancel.is_set
    return cancel


def _seeds(problem: RouteProblem, pool: SeedPool | None, a: Port, b: Port, month: int,
           previous: RoutePlan | None, position) -> tuple[list[TrackSeed], list]:
    out, genes = [], []
    if previous is not None:
        lon, lat, t = previous.track()
        if position is not None:
            s = shift_track(lon, lat, t, previous.leg_rpm(), problem.dep_lon_deg,
                            problem.dep_lat_deg, problem.depart_s)
        else:
            s = TrackSeed("previous_plan", lon, lat, previous.leg_rpm())
        if s is not None and s.lon_deg.size >= 2:
            out.append(s)
    if pool is not None:
        stored = pool.get(pool_key(_port_id(a), _port_id(b), month))
        if stored is not None:
            out.append(TrackSeed("pool", np.array(stored.lon_deg), np.array(stored.lat_deg),
                                 np.array(stored.rpm)))
            if stored.genes:
                genes.append(("pool", np.array(stored.genes)))
    return out, genes


def _offer(pool: SeedPool, problem: RouteProblem, a: Port, b: Port, month: int,
           ev: RouteEvaluation, source: str, genes: np.ndarray | None) -> None:
    pool.offer(Seed(pool_key(_port_id(a), _port_id(b), month),
                    tuple(map(float, ev.lon_deg[0])), tuple(map(float, ev.lat_deg[0])),
                    tuple(map(float, ev.legs["rpm"][0])), problem.objective,
                    float(ev.objective[0]), float(ev.violation[0]), float(ev.fuel_t[0]),
                    source, genes=() if genes is None else tuple(map(float, genes))))


def _legs_of(ev: RouteEvaluation, pre: RouteEvaluation | None,
             post: RouteEvaluation | None) -> list[RouteEvaluation]:
    return [e for e in (pre, ev, post) if e is not None]


def _assemble(ports, problems, results, baselines, sources, approaches, env, spec, method,
              objective, depart_s, rta_s, leg_rtas, gens, evals, compute_s,
              deadlines) -> RoutePlan:
    wps: list[Waypoint] = []
    flags = 0
    plan_parts, base_parts, spans, fixed = [], [], [], []
    for k, ev in enumerate(results):
        pre, post = approaches[k]
        parts = _legs_of(ev, pre, post)
        plan_parts.extend(parts)
        if baselines:
            base_parts.extend(_legs_of(baselines[k][2], pre, post))
        for j, part in enumerate(parts):
            m = part.legs["rpm"].shape[1]
            weather = env.weather(part.lon_deg[0, :m], part.lat_deg[0, :m], part.time_s[0, :m])
            names = {}
            if j == 0:
                names[0] = ports[k].name
            if j == len(parts) - 1:
                names[m] = ports[k + 1].name
            w = waypoints_from_evaluation(part, weather, names)
            start = max(len(wps) - 1, 0)
            if wps:  # the junction node carries the next part's leg values
                wps[-1] = dataclasses.replace(w[0], port=wps[-1].port or w[0].port)
                w = w[1:]
            wps.extend(w)
            if part is ev and sources[k] == "canal":
                fixed.append((start, len(wps) - 1))
            elif part is ev and sources[k] != "strait":
                spans.append((start, len(wps) - 1))
            if part is ev and sources[k] != "strait":  # approaches and strait passages are
                # computed against land, clearance and depth: their flags inform, not decide
                flags |= int(part.flags[0]) & ~2
        if float(parts[-1].eta_s[0]) > deadlines[k] and sources[k] not in ("strait", "canal"):
            flags |= 2  # inserted points carry no user RTA: a fixed passage's time is made
            # up on the optimised leg after it
    fuel = sum(float(ev.fuel_t[0]) for ev in plan_parts)
    dist = sum(float(ev.distance_m[0]) for ev in plan_parts) / 1852.0
    eta = float(plan_parts[-1].eta_s[0])
    b_fuel = sum(float(e.fuel_t[0]) for e in base_parts) if baselines else float("nan")
    b_dist = sum(float(e.distance_m[0]) for e in base_parts) / 1852.0 if baselines else 0.0
    b_eta = float(base_parts[-1].eta_s[0]) if baselines else float("nan")
    b_ok = all(bool(b[2].feasible[0]) for b in baselines) if baselines else False
    b_track = tuple((float(la), float(lo)) for e in base_parts
                    for lo, la in zip(e.lon_deg[0], e.lat_deg[0], strict=True))
    return RoutePlan(
        plan_id=uuid.uuid4().hex[:12], method=method, seed_source=sources[0],
        objective=objective, ship_name=getattr(spec, "name", ""), cycle_id=env.cycle_id,
        departure_s=depart_s, rta_s=rta_s, eta_s=eta, feasible=flags == 0,
        infeasible_reasons=reasons_of(flags), total_fuel_t=fuel, total_distance_nm=dist,
        total_time_s=eta - depart_s, baseline_fuel_t=b_fuel,
        baseline_method="+".join(sorted({b[0] for b in baselines})) if baselines else "",
        baseline_distance_nm=b_dist, baseline_eta_s=b_eta, baseline_feasible=b_ok,
        baseline_rpm=float(baselines[0][1]) if baselines else float("nan"),
        compute_time_s=compute_s, waypoints=tuple(wps),
        ports=tuple(p.name for p in ports), stage_s=problems[0].stage_s, generations=gens,
        evaluations=evals,
        vessel_max_wave_m=float(problems[0].limits.max_hs_m or float("nan")),
        vessel_max_wind_m_s=float(problems[0].limits.max_wind_m_s or float("nan")),
        baseline_track=b_track, leg_rtas_s=tuple(leg_rtas), optimised_spans=tuple(spans),
        extra={"fixed_passages": tuple(fixed)} if fixed else {},
    )
