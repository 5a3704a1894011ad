"""High-level planning API: a frozen `VoyageRequest` and `PlanOptions` -> frozen `RoutePlan`.

`plan` resolves ports, splits a multi-port voyage into legs with their own time windows
(`plan_prepare`), gathers seeds (seed pool, previous plan shifted to the ship's position),
runs the chosen method per leg within the wall-time budget, computes the constant-RPM
baseline with the same evaluator, stores the result in the seed pool (`plan_legs`) and joins
everything into one checked plan that states what it was made with. `plan_voyage` is the same
call with keyword arguments.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence
from datetime import timedelta
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .coastal_depth import with_coarse_coast_note
from .depth_setup import with_depth_report
from .ensemble_report import ensemble_block, with_ensemble
from .forecast_statement import forecast_statement
from .ga.loop import GAConfig
from .geo.depth import Bathymetry
from .geo.landmask import LandMask
from .geo.ports import Port
from .geo.zones import Zones
from .method_context import Progress
from .objectives import Economics, objective_block
from .plan_assembly import assemble_plan
from .plan_checks import checked_plan
from .plan_legs import LegRun, sail_legs
from .plan_prepare import PreparedVoyage, prepare_voyage
from .plan_setup import TimeLike, to_posix_s
from .plan_timing import PlanClock, previous_checks_s
from .plan_types import RoutePlan
from .replan_keep import carried_legs, kept_or_new, with_search_effort
from .replan_retime import retimed_legs
from .request import (
    CancelHook,
    ForecastInput,
    PlanOptions,
    ShipInput,
    VoyageRequest,
    file_list,
    voyage_times,
)
from .river_passages import with_river_passages
from .route.clearance import DEFAULT_CLEARANCE
from .route.risk import RiskSpec
from .voyage.plan_calls import with_port_calls
from .voyage.port_calls import PortCall
from .voyage.stage_length import RTA_TOLERANCE_S
from .voyage_ship import loading_block

if TYPE_CHECKING:
    import xarray as xr


def deadline_s(call: PortCall | None, rta_s: float | None) -> float:
    """Latest arrival at a leg's end port (the RTA at the destination; inf: none)."""
    limits = [t for t in (rta_s, call.latest_s if call is not None else None) if t is not None]
    return min(limits) if limits else float("inf")


def plan(request: VoyageRequest, options: PlanOptions | None = None,
         forecast: ForecastInput = None) -> RoutePlan:
    """Plan `request` on `forecast` (a sampler, a canonical Dataset, or None for calm water)
    with `options` (defaults: the seed GA, 3 s, seed 0); see `plan_voyage` for the meaning of
    each field. Raises InvalidVoyageError naming a bad input; a cancelled run returns the
    best plan so far (PlanCancelledError before any route was found)."""
    options = options or PlanOptions()
    clock = PlanClock(checks_measured_s=previous_checks_s(options.previous_plan))
    prep = prepare_voyage(request, options, forecast)
    # a re-plan is never silently worse than the previous plan's remainder on this forecast
    carried = carried_legs(prep, options)
    clock.lap("set-up")
    run = sail_legs(request, options, prep, clock)
    if options.previous_plan is not None:  # a re-plan's short search may arrive hours early
        run = retimed_run(prep, run)
    new = finished_plan(request, options, prep, run, clock)
    return with_search_effort(kept_or_new(
        new, carried, prep, options, run,
        lambda legs: finished_plan(request, options, prep, legs, clock)), options)


def retimed_run(prep: PreparedVoyage, run: LegRun) -> LegRun:
    """`run` with its legs re-timed to arrive on time (`replan_retime`), and its words."""
    timed = retimed_legs(prep, run.results, run.sources, run.approaches, prep.depart_s,
                         "the new search's route")
    if not timed.said:
        return run
    return dataclasses.replace(run, results=list(timed.results),
                               approaches=list(timed.approaches),
                               arrivals=list(timed.arrivals),
                               warnings=[*run.warnings, timed.said])


def finished_plan(request: VoyageRequest, options: PlanOptions, prep: PreparedVoyage,
                  run: LegRun, clock: PlanClock) -> RoutePlan:
    """The legs joined into one plan, with the schedule, model, RTA, depth, route-check,
    forecast and objective statements."""
    n = len(run.results)
    deadlines = [deadline_s(prep.call_at.get(k + 1), prep.rta_s if k == n - 1 else None)
                 + prep.rta_tolerance_s for k in range(n)]
    out = assemble_plan(list(prep.ports), run.problems, run.results, run.baselines,
                        run.sources, run.approaches, prep.env, prep.spec, options.method,
                        request.objective, prep.depart_s, prep.rta_s, list(prep.leg_rtas),
                        run.generations, run.evaluations, clock.elapsed_s(), deadlines)
    if prep.schedule is not None:
        out = with_port_calls(out, prep.schedule_legs, prep.schedule, run.arrivals,
                              list(prep.ports), prep.rta_tolerance_s)
    if prep.model_notes:
        from .learned.select import plan_warnings

        model_warnings = (*prep.model_notes, *plan_warnings(prep.env.model, out))
        out = dataclasses.replace(out, warnings=(*out.warnings, *model_warnings))
    if prep.rta_warning:
        out = dataclasses.replace(out, warnings=(*out.warnings, prep.rta_warning))
    narrows = tuple(dict.fromkeys(pt for p in run.problems for pt in p.limits.clearance.narrows))
    check_limits = dataclasses.replace(prep.limits, clearance=dataclasses.replace(
        prep.limits.clearance, narrows=narrows))
    out = checked_plan(with_depth_report(out, prep.limits.under_keel, run.warnings), prep.land,
                       check_limits, request.clearance_nm)
    out = with_coarse_coast_note(with_river_passages(out, list(prep.river_rows)),
                                 prep.limits.under_keel, prep.land)
    out = with_ensemble(out, *ensemble_block(out, prep.env, prep.land, run.member_legs,
                                             prep.risk, prep.rta_tolerance_s))
    block, said = forecast_statement(prep.env.sampler, out, options.persistence_h)
    goal = objective_block(prep.terms, out.total_fuel_t, out.total_time_s / 3600.0,
                           out.total_distance_nm)
    clock.lap("checks")
    late = clock.overrun_warning(options.budget_s)
    return dataclasses.replace(out, warnings=(*out.warnings, *said, *prep.terms.notes,
                                              *clock.passage_statement(),
                                              *([late] if late else [])),
                               extra={**out.extra, "forecast": block, "objective": goal,
                                      "timing_s": clock.block(options.budget_s),
                                      "land_repairs": run.repairs,
                                      # where the search kept the narrow-water clearance
                                      # (`route.lane_narrows`); a re-plan under way keeps them
                                      "lane_narrows": [list(p) for p in narrows],
                                      **loading_block(prep.spec)})


def plan_voyage(
    origin: str | Port,
    destination: str | Port,
    depart: TimeLike,
    rta: TimeLike | timedelta,
    ship: ShipInput,
    forecast: ForecastInput = None,
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
    cancel: CancelHook | None = None,
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
    climatology: xr.Dataset | None = None,
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
    risk: str | RiskSpec | None = None,
    p_hs_max: float | None = None,
    p_late_max: float | None = None,
    open_sea_clearance_nm: float = DEFAULT_CLEARANCE.open_sea_nm,
    approach_clearance_nm: float = DEFAULT_CLEARANCE.approach_nm,
    approach_zone_nm: float = DEFAULT_CLEARANCE.approach_zone_nm,
) -> RoutePlan:
    """Plan a voyage and return a frozen RoutePlan (`plan` with keyword arguments).

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
    (`learned.select.resolve_model`: physics (alias fast), physics-direct (solved on every
    leg), kwon, profile:FILE, learned:FILE; "" = the ship file's `performance_model` entry or
    physics); the choice is stated in the plan's warnings.
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
    (`voyage.stage_length`), shared among its spans between straits and canals.
    `port_calls` (or `via` with `via_rta` as latest arrivals) make a multi-port voyage whose
    leg times are scheduled together for the least fuel (`voyage.schedule`); a plan is on
    time when it arrives within `rta_tolerance_s` of each deadline.
    `risk` (`mean`, `cvar:ALPHA`, `worst` or a `RiskSpec`) plans on every member of an
    ensemble forecast: the seed GA minimises that measure of the members' objective under
    the chance constraints P(Hs > limit) <= `p_hs_max` and P(late) <= `p_late_max` (None: 0);
    without it an ensemble is planned on its members' mean. Either way an ensemble plan
    states its spread over the members (`ensemble_report`).
    `open_sea_clearance_nm`, `approach_clearance_nm` (near the span ends, within
    `approach_zone_nm`, and in narrow water): the search's clearance rule (`route.clearance`).
    """
    depart_s, rta_s = voyage_times(depart, rta)
    request = VoyageRequest(
        origin, destination, depart_s, rta_s, ship, via=tuple(via),
        via_rta_s=tuple(None if t is None else to_posix_s(t) for t in via_rta),
        port_calls=tuple(port_calls), rta_tolerance_s=rta_tolerance_s, objective=objective,
        economics=economics, ship_model=ship_model, loading=loading,
        bathymetry=bathymetry if isinstance(bathymetry, Bathymetry) else file_list(bathymetry),
        default_bathymetry=default_bathymetry, ukc_margin_m=ukc_margin_m,
        zones=zones if isinstance(zones, Zones) else file_list(zones),
        clearance_nm=clearance_nm, approaches_given=file_list(approaches_given) or (),
        approach_nm=approach_nm, approach_rpm=approach_rpm, coastal_passage=coastal_passage)
    options = PlanOptions(
        method=method, budget_s=budget_s, seed=seed, stage_hours=stage_hours,
        ga_config=ga_config, stall_generations=stall_generations,
        max_generations=max_generations, max_evaluations=max_evaluations,
        with_baseline=with_baseline, previous_plan=previous_plan, position=position,
        seed_pool_dir=seed_pool_dir, progress=progress, cancel=cancel, limits=limits,
        land=land, cycle_id=cycle_id, persistence_h=persistence_h,
        climatology=climatology, risk=risk, p_hs_max=p_hs_max, p_late_max=p_late_max,
        open_sea_clearance_nm=open_sea_clearance_nm,
        approach_clearance_nm=approach_clearance_nm, approach_zone_nm=approach_zone_nm)
    return plan(request, options, forecast)
