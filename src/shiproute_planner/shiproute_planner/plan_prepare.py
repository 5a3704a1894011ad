"""A voyage request made ready to plan: the ship's model, environment and limits, the ports
with canals and straits inserted, the port calls' schedule and each leg's target arrival, and
the notes the plan will state (the first step of `planning.plan`)."""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from .checks.parameters import require_number
from .coastal_passages import passage_rules, passages_note
from .depth_setup import depth_limits
from .errors import InvalidVoyageError, ParameterError
from .forecast_statement import prepare_forecast
from .geo.landmask import LandMask, default_land_mask
from .geo.ports import Port, resolve_port
from .objectives import ObjectiveTerms, objective_terms
from .plan_checks import zone_limits
from .plan_setup import chosen_model, make_environment, route_limits, rta_warning_of
from .request import ForecastInput, PlanOptions, ShipInput, VoyageRequest
from .river_passages import river_calls, river_times
from .route.canals import Canal, route_canals
from .route.clearance import ClearanceRule
from .route.environment import Environment
from .route.given_approach import Approach, load_approaches
from .route.problem import RouteLimits
from .route.risk import RiskSpec, parse_risk
from .ship.spec import ShipSpec
from .shoal_passages import route_shoals
from .straits import route_straits
from .voyage.lat_bound import voyage_lat_bound
from .voyage.legs import voyage_schedule
from .voyage.port_calls import PortCall
from .voyage.schedule import FuelRate, LegSpec, Schedule
from .voyage.spans import SpanPlan, span_plan
from .voyage.stage_length import check_rta_tolerance_s
from .voyage_ship import loaded_ship


@dataclass(frozen=True)
class PreparedVoyage:
    """Everything the leg loop needs, fixed before the first leg is planned."""

    land: LandMask
    env: Environment
    spec: ShipSpec | None  # None for a bare performance model
    limits: RouteLimits
    terms: ObjectiveTerms
    given: tuple[Approach, ...]
    ports: tuple[Port, ...]
    depart_s: float  # the ship's time when re-planning under way
    rta_s: float
    rta_tolerance_s: float
    call_at: dict[int, PortCall]  # port index -> its call
    canal_legs: dict[int, tuple[Canal, bool]]  # leg -> (canal, sailed in reverse)
    strait_legs: dict[int, Any]
    schedule: Schedule | None  # of a multi-port voyage
    schedule_legs: list[LegSpec]
    fuel_rate: FuelRate | None
    leg_rtas: tuple[float, ...]  # the schedule's arrival per leg, the RTA for the last
    search_rtas: tuple[float, ...]  # what each leg aims at (earliest arrival when late)
    rta_warning: str
    model_notes: tuple[str, ...]
    warnings: tuple[str, ...]
    river_rows: tuple[dict[str, Any], ...] = ()  # river passages (the plan's extra)
    risk: RiskSpec | None = None  # the ensemble risk measure (None: the members' mean)
    spans: SpanPlan | None = None  # user's leg, stage length and target stages per span


def ship_choice(ship: ShipInput, ship_model: str, loading: str) -> tuple[ShipInput, str, str]:
    """(ship, model choice, loading) as the planner resolves them: "physics-direct" is the
    ship's physics solved on every leg (in its loading condition), "fast" names "physics"."""
    if ship_model == "physics-direct":
        from .ship import PhysicsModel, load_ship

        if not isinstance(ship, str | Path | ShipSpec):
            raise InvalidVoyageError("give ship_model with a ship name/file, not with a model")
        spec = loaded_ship(ship, loading) if loading else (
            ship if isinstance(ship, ShipSpec) else load_ship(ship))
        return PhysicsModel(spec), "", ""
    return ship, "physics" if ship_model == "fast" else ship_model, loading


def resolve_ports(request: VoyageRequest, land: LandMask) -> list[Port]:
    """Origin, vias (or the port calls' ports) and destination as charted ports."""
    via = [c.port for c in request.port_calls] if request.port_calls else list(request.via)
    return [p if isinstance(p, Port) else resolve_port(p, land)
            for p in (request.origin, *via, request.destination)]


def start_of(ports: list[Port], options: PlanOptions, land: LandMask,
             depart_s: float) -> float:
    """Departure time; under way the first port becomes the ship's position (not on land)."""
    if options.position is None:
        return depart_s
    lat, lon, now_s = options.position
    if land.is_land(np.array([lon]), np.array([lat]))[0]:
        raise InvalidVoyageError(f"ship position {lat:.4f},{lon:.4f} is on land")
    ports[0] = Port("ship position", "", float(lat), float(lon))
    return float(now_s)


def calls_of(request: VoyageRequest, depart_s: float) -> list[PortCall | None]:
    """The port calls, or the `via` ports whose `via_rta_s` is a latest arrival."""
    if request.port_calls:
        return list(request.port_calls)
    via, via_rta = request.via, request.via_rta_s
    rtas: Sequence[float | None] = list(via_rta) + [None] * (len(via) - len(via_rta))
    out: list[PortCall | None] = []
    for p, t in zip(via, rtas, strict=False):
        name = p.name if isinstance(p, Port) else str(p)
        if t is not None and t <= depart_s:
            raise InvalidVoyageError(f"via {name}: RTA is not after the departure")
        out.append(PortCall(name, None, t, 0.0))
    return out


def risk_of(options: PlanOptions) -> RiskSpec | None:
    """The ensemble risk measure with its chance constraints (bounds need a measure)."""
    if options.risk is None and (options.p_hs_max is not None or options.p_late_max is not None):
        raise ParameterError("p_hs_max / p_late_max bound a risk-aware plan: give risk too")
    if options.risk is None or isinstance(options.risk, RiskSpec):
        return options.risk
    return parse_risk(options.risk, options.p_hs_max, options.p_late_max)


def prepare_voyage(request: VoyageRequest, options: PlanOptions,
                   forecast: ForecastInput) -> PreparedVoyage:
    """Check and set up `request` (raises InvalidVoyageError naming what is wrong)."""
    if options.stage_hours is not None:
        require_number("stage_hours", options.stage_hours)
    tolerance_s = check_rta_tolerance_s(request.rta_tolerance_s)
    risk = risk_of(options)
    land = options.land or default_land_mask()
    ship, choice, loading = ship_choice(request.ship, request.ship_model, request.loading)
    model, model_notes = chosen_model(loaded_ship(ship, loading), choice)
    env, spec = make_environment(model, forecast)
    terms = objective_terms(request.objective, dict(getattr(spec, "economics", ()) or ()),
                            request.economics)
    if options.cycle_id:
        env = dataclasses.replace(env, cycle_id=options.cycle_id)
    lim = route_limits(spec, dict(options.limits) if options.limits is not None else None)
    lim, warnings = depth_limits(lim, spec, request.bathymetry, request.default_bathymetry,
                                 request.ukc_margin_m)
    lim, zone_notes = zone_limits(lim, request.zones)
    lim = dataclasses.replace(lim, clearance=ClearanceRule(
        options.open_sea_clearance_nm, options.approach_clearance_nm, options.approach_zone_nm))
    warnings += zone_notes
    given = load_approaches(request.approaches_given)
    ports = resolve_ports(request, land)
    warnings += [p.note for p in ports if p.note]
    depart_s = start_of(ports, options, land, request.depart_s)
    rta_s = request.rta_s
    if not rta_s > depart_s:
        raise InvalidVoyageError("the RTA must be after the departure time")
    depart_s, rta_s, river_notes, river_rows = river_times(ports[0], ports[-1], depart_s,
                                                           rta_s)
    if not rta_s > depart_s:
        raise InvalidVoyageError("the river passages at the voyage's ends take longer than "
                                 "the time to the RTA: " + "; ".join(river_notes))
    calls, call_notes, call_rows = river_calls(ports[1:-1], calls_of(request, depart_s))
    warnings += river_notes + call_notes
    user_ports = list(ports)  # the user's ports: stage length and budget follow their legs
    ports, canal_legs, calls, canal_notes = route_canals(ports, spec, calls)
    warnings += canal_notes
    strait_legs: dict = {}
    if request.coastal_passage:
        draft_m = max(spec.condition.draft_fore_m, spec.condition.draft_aft_m) if spec else 0.0
        ports, canal_legs, strait_legs, calls, strait_notes = route_straits(
            ports, canal_legs, calls, draft_m)
        warnings += strait_notes
        ports, canal_legs, strait_legs, calls, shoal_notes = route_shoals(
            ports, canal_legs, strait_legs, calls, lim.under_keel,
            passage_rules(lim.under_keel).required_depth_m)
        warnings += shoal_notes
        warnings.append(passages_note(passage_rules(lim.under_keel)))
    lim, lat_notes = voyage_lat_bound(lim, ports, fixed="lat_bound_deg" in (options.limits or {}))
    warnings += lat_notes
    sched, rate = None, None
    sched_legs: list[LegSpec] = []
    call_at: dict[int, PortCall] = {}
    leg_rtas = [rta_s]
    if len(ports) > 2:
        call_at = {k + 1: c for k, c in enumerate(calls) if c is not None}
        sched_legs, sched, notes, rate = voyage_schedule(
            ports, call_at, canal_legs, depart_s, rta_s, env.model, lim.rpm_min, lim.rpm_max,
            land if options.position is not None else None)
        warnings += notes
        leg_rtas = [*sched.arrival_s[:-1], rta_s]  # the last leg aims at the RTA itself
    env = dataclasses.replace(env, sampler=prepare_forecast(
        env.sampler, depart_s, rta_s, options.persistence_h, options.climatology), risk=risk)
    rta_warning, earliest_s = rta_warning_of(ports, depart_s, rta_s, spec)
    # an RTA beyond reach is searched best effort: over the time the great circle takes at
    # full speed (a lower bound), lateness being a violation the search minimises; a
    # schedule (ports, canals, straits) never asks a leg for more than the ship can do
    search_rtas = [*leg_rtas[:-1], earliest_s] if rta_warning else list(leg_rtas)
    spans = span_plan(user_ports, ports, set(canal_legs) | set(strait_legs), search_rtas,
                      depart_s, options.stage_hours)
    return PreparedVoyage(
        land, env, spec, lim, terms, tuple(given), tuple(ports), depart_s, rta_s, tolerance_s,
        call_at, canal_legs, strait_legs, sched, sched_legs, rate,
        tuple(float(t) for t in leg_rtas), tuple(float(t) for t in search_rtas), rta_warning,
        tuple(model_notes), tuple(warnings), tuple(river_rows + call_rows), risk,
        spans)
