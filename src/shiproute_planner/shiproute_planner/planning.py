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
from shiproute_core.geodesy import inverse
from shiproute_core.units import M_PER_NM

from .checks.parameters import require_number
from .depth_setup import depth_limits, with_depth_report
from .errors import InvalidVoyageError, PlanCancelledError
from .forecast_statement import forecast_statement, prepare_forecast
from .ga.loop import GAConfig
from .ga.pool import SeedPool
from .geo.depth import Bathymetry
from .geo.landmask import LandMask, default_land_mask
from .geo.ports import Port, resolve_port
from .geo.zones import Zones
from .method_context import MethodContext, Progress, compute_baseline
from .methods import get_method
from .plan_assembly import assemble_plan
from .plan_checks import checked_plan, zone_limits
from .plan_seeds import leg_seeds, offer_to_pool
from .plan_types import RoutePlan
from .route.approach import (
    sail_approach,
)
from .route.canals import route_canals, sail_canal
from .route.environment import Environment
from .route.given_approach import load_approaches
from .route.problem import RouteLimits
from .route.voyage_legs import leg_setup

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
    from shiproute_weather.scenarios import scenario_dataset, scenario_names

    names = [name_or_path] if isinstance(name_or_path, str | Path) else list(name_or_path)
    if len(names) == 1 and not Path(names[0]).exists() and names[0] in scenario_names():
        return scenario_dataset(str(names[0]))
    for n in names:
        if not Path(n).exists():
            raise InvalidVoyageError(
                f"forecast {str(n)!r} is neither a file nor a bundled scenario "
                f"({', '.join(scenario_names())})")
    from shiproute_weather.loaders import open_forecast

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
            from shiproute_weather.sampling import ForecastSampler

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


def _leg_rtas(ports: list[Port], depart_s: float, rta_s: float,
              via_rtas: Sequence[TimeLike | None]) -> list[float]:
    """RTA per leg: given ones, the rest split in proportion to great-circle distance."""
    n = len(ports) - 1
    given = [None if v is None else to_posix_s(v) for v in via_rtas] + [None] * n
    given = [*given[: n - 1], rta_s]
    d = np.array([float(inverse(a.lon_deg, a.lat_deg, b.lon_deg, b.lat_deg)[1])
                  for a, b in itertools.pairwise(ports)])
    out, t_prev, k_prev = [], depart_s, -1
    for k in range(n):
        if given[k] is None:
            continue
        span = d[k_prev + 1: k + 1]
        cum = np.cumsum(span) / max(span.sum(), 1.0)
        out.extend(t_prev + (given[k] - t_prev) * cum)
        t_prev, k_prev = given[k], k
    if any(b <= a for a, b in zip([depart_s, *out[:-1]], out, strict=True)):
        raise InvalidVoyageError("leg RTAs must increase along the voyage")
    return out


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
    stage_hours: float = 12.0,
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
    """
    t0 = time.perf_counter()
    require_number("stage_hours", stage_hours)
    land = land or default_land_mask()
    ship, model_notes = _chosen_model(ship, ship_model)
    env, spec = make_environment(ship, forecast)
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
    ports, canal_legs, via_rta, canal_notes = route_canals(ports, spec, list(via_rta))
    warnings += canal_notes
    leg_rtas = _leg_rtas(ports, depart_s, rta_s, via_rta)
    env = dataclasses.replace(env, sampler=prepare_forecast(env.sampler, depart_s, rta_s,
                                                            persistence_h, climatology))
    rta_warning, earliest_s = _rta_warning(ports, depart_s, rta_s, spec)
    # an RTA beyond reach is searched best effort: over the time the great circle takes at
    # full speed (a lower bound), lateness being a violation the search minimises
    search_rtas = (_leg_rtas(ports, depart_s, earliest_s, via_rta) if rta_warning
                   else leg_rtas)
    is_cancelled = _cancel_fn(cancel)
    rng = seed if isinstance(seed, np.random.Generator) else np.random.default_rng(seed)
    pool = SeedPool(seed_pool_dir) if seed_pool_dir is not None else None
    month = datetime.fromtimestamp(depart_s, UTC).month
    fn = get_method(method)
    dists = np.array([float(inverse(a.lon_deg, a.lat_deg, b.lon_deg, b.lat_deg)[1])
                      for a, b in itertools.pairwise(ports)])
    results, baselines, problems, sources, approaches = [], [], [], [], []
    gens = evals = 0
    leg_depart = depart_s
    for k, (a, b) in enumerate(itertools.pairwise(ports)):
        if k in canal_legs:  # a fixed passage: sailed along the canal at its transit speed
            canal, rev = canal_legs[k]
            sea_rpm = float(results[-1].legs["rpm"][0, -1]) if results else None
            lead_in, ev, lead_out, rpm_c, canal_problem = sail_canal(
                env, canal, rev, leg_depart, lim, stage_hours * 3600.0, sea_rpm)
            results.append(ev)
            sources.append("canal")
            problems.append(canal_problem)
            if with_baseline:
                baselines.append(("canal", rpm_c, ev))
            approaches.append((lead_in, lead_out))
            leg_depart = float((lead_out or ev).eta_s[0])
            continue
        under_way = k == 0 and position is not None
        leg = leg_setup(a, b, env, lim, land, leg_depart, search_rtas[k], approach_nm=approach_nm,
                        approach_rpm=approach_rpm, coastal_passage=coastal_passage,
                        stage_hours=stage_hours, objective=objective,
                        under_way=under_way, previous_plan=previous_plan if under_way else None,
                        position=position if under_way else None, given=given)
        problem, pre, ap_arr, rpm_ap = leg.problem, leg.pre, leg.ap_arr, leg.rpm_ap
        seeds, gene_seeds = leg_seeds(problem, pool, a, b, month,
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
                            k, time.perf_counter(), ga_config, stall_generations=stall_generations,
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
            offer_to_pool(pool, problem, a, b, month, res.evaluation, res.seed_source, res.genes)
        leg_depart = float(res.evaluation.eta_s[0])
        post = sail_approach(env, ap_arr, rpm_ap, leg_depart, lim) if ap_arr else None
        if post is not None:
            leg_depart = float(post.eta_s[0])
        approaches.append((pre, post))
    land.fine_coast.save()  # coastal cells this plan resolved: later processes start with them
    plan = assemble_plan(ports, problems, results, baselines, sources, approaches, env, spec,
                     method, objective, depart_s, rta_s, leg_rtas, gens, evals,
                     time.perf_counter() - t0)
    if model_notes:
        from .learned.select import plan_warnings

        notes = model_notes + plan_warnings(env.model, plan)
        plan = dataclasses.replace(plan, warnings=plan.warnings + notes)
    if rta_warning:
        plan = dataclasses.replace(plan, warnings=(*plan.warnings, rta_warning))
    plan = checked_plan(with_depth_report(plan, lim.under_keel, warnings), land, lim,
                        clearance_nm)
    block, said = forecast_statement(env.sampler, plan, persistence_h)
    return dataclasses.replace(plan, warnings=(*plan.warnings, *said),
                               extra={**plan.extra, "forecast": block})


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
                  for a, b in itertools.pairwise(ports)) / M_PER_NM
    need_kn = dist_nm / ((rta_s - depart_s) / 3600.0)
    top_kn = max_calm_speed_kn(spec)
    earliest_s = depart_s + dist_nm / top_kn * 3600.0
    if need_kn <= top_kn:
        return "", rta_s
    return (f"RTA unreachable: {dist_nm:.0f} NM (great circle, the shortest possible) in "
            f"{(rta_s - depart_s) / 3600:.1f} h needs {need_kn:.1f} kn, the ship makes at most "
            f"{top_kn:.1f} kn in calm water; best-effort plan (earliest arrival)"), earliest_s


def _cancel_fn(cancel: Any) -> Callable[[], bool]:
    if cancel is None:
        return lambda: False
    if hasattr(cancel, "is_set"):
        return cancel.is_set
    return cancel


