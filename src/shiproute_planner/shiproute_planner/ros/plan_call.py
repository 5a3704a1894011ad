"""One plan from the planner node's parameters: where the run starts, the `VoyageRequest` and
`PlanOptions` they name, and the plan's files."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

from ..objectives import Economics
from ..plan_types import RoutePlan
from ..request import PlanOptions, VoyageRequest
from ..voyage.node_calls import calls_ahead, node_port_calls
from ..voyage.port_calls import PortCall
from ..voyage_params import parse_utc
from .cycle_packer import hs_field_at
from .member_packer import EnsembleCycle, ensemble_hs_field_at
from .parameters import paths
from .replan_policy import at_departure_port


def plan_forecast(forecast: Any) -> Any:
    """What `plan_voyage` is given: the sampler of a deterministic cycle, or the canonical
    dataset with its `member` dimension of an ensemble / multi-model cycle (no member is
    dropped or averaged here: planning on members is `plan_voyage`'s)."""
    return forecast.dataset if isinstance(forecast, EnsembleCycle) else forecast


def economics(p: Callable[[str], Any]) -> Economics:
    """The co2/cost figures the parameters set (None where the ship file decides)."""
    price, rate = float(p("fuel_price_usd_per_t")), float(p("charter_usd_per_day"))
    return Economics(str(p("fuel_type")) or None, price if price >= 0 else None,
                     rate if rate >= 0 else None)


def risk_keywords(p: Callable[[str], Any]) -> dict[str, Any]:
    """`plan_voyage`'s risk keywords from the parameters (none when `risk` is '')."""
    risk = str(p("risk")).strip()
    if not risk:
        return {}
    return {"risk": risk, "p_hs_max": float(p("p_hs_max")),
            "p_late_max": float(p("p_late_max"))}


def node_request(p: Callable[[str], Any], *, origin: str, depart_s: float,
                 rta_s: float | None, objective: str, calls: tuple[PortCall, ...]
                 ) -> VoyageRequest:
    """The voyage the parameters name (`objective` and `rta_s` override them when given)."""
    return VoyageRequest(
        origin, str(p("destination")), depart_s,
        parse_utc(str(p("rta"))) if rta_s is None else rta_s, str(p("ship")),
        port_calls=calls, rta_tolerance_s=float(p("rta_tolerance_s")),
        objective=objective or str(p("objective")), economics=economics(p),
        ship_model=str(p("ship_model")), loading=str(p("loading")),
        bathymetry=tuple(paths(str(p("bathymetry_files")))) or None,
        default_bathymetry=bool(p("default_bathymetry")),
        ukc_margin_m=float(p("ukc_margin_m")),
        zones=tuple(paths(str(p("zones_files")))) or None,
        clearance_nm=float(p("clearance_nm")),
        approaches_given=tuple(paths(str(p("approach_files")))))


def plan_from_parameters(p: Callable[[str], Any], forecast: Any, *, cycle_id: str,
                         origin: str, depart_s: float, budget_s: float,
                         previous: RoutePlan | None,
                         position: tuple[float, float, float] | None,
                         progress: Callable[[Any], None] | None, cancel: Any,
                         objective: str = "", rta_s: float | None = None,
                         seed_offset: int = 0) -> RoutePlan:
    """Plan with the voyage, ship, method and data files named by the parameters (`p(name)`
    gives a parameter's value); the run's own inputs come as arguments (`objective` and
    `rta_s` override the parameters for one plan of a time-fuel front)."""
    from ..planning import plan

    calls = calls_ahead(node_port_calls(str(p("port_calls")), depart_s), previous,
                        position[2] if position else None)
    request = node_request(p, origin=origin, depart_s=depart_s, rta_s=rta_s,
                           objective=objective, calls=tuple(calls))
    options = PlanOptions(
        method=str(p("method")), budget_s=budget_s, seed=int(p("rng_seed")) + seed_offset,
        stage_hours=float(p("stage_hours")) or None, previous_plan=previous,
        position=position, seed_pool_dir=str(p("seed_pool_dir")) or None, progress=progress,
        cancel=cancel, cycle_id=cycle_id,
        open_sea_clearance_nm=float(p("open_sea_clearance_nm")),
        approach_clearance_nm=float(p("approach_clearance_nm")),
        approach_zone_nm=float(p("approach_zone_nm")), **risk_keywords(p))
    return plan(request, options, plan_forecast(forecast))


def front_from_parameters(p: Callable[[str], Any], forecast: Any, *, cycle_id: str,
                          depart_s: float, position: tuple[float, float, float] | None,
                          budget_s: float, points: int, cancel: Any) -> Any:
    """The time-fuel front of the voyage from the ship (or the origin) to the RTA: `points`
    plans sharing `budget_s`, from the earliest safe arrival to the RTA."""
    from ..front import build_front, top_speed_s

    def one(k: int, objective: str, rta_s: float, previous: RoutePlan | None) -> RoutePlan:
        return plan_from_parameters(
            p, forecast, cycle_id=cycle_id, origin=str(p("origin")), depart_s=depart_s,
            budget_s=budget_s / points, previous=previous, position=position, progress=None,
            cancel=cancel, objective=objective, rta_s=rta_s, seed_offset=k)

    start = (str(p("origin")) if position is None
             else f"{position[0]:.5f},{position[1]:.5f}")
    top = top_speed_s(start, str(p("destination")), str(p("ship")), str(p("loading")))
    return build_front(one, depart_s, parse_utc(str(p("rta"))), points, top)


def run_start(origin: str, position: tuple[float, float, float] | None,
              previous: RoutePlan | None, departure_time: str, departure_radius_nm: float,
              ) -> tuple[float, tuple[float, float, float] | None]:
    """(departure time [POSIX s], position to plan from): the ship's fix and time, or the
    origin port at `departure_time` without one. A first plan of a ship still within
    `departure_radius_nm` of the origin starts at the port (the seed pool is keyed by ports)."""
    if position is None:
        return parse_utc(departure_time), None
    if previous is None and at_departure_port(origin, position[0], position[1],
                                              departure_radius_nm):
        return position[2], None
    return position[2], position


def write_outputs(plan: RoutePlan, sampler: Any, out_dir: str, png: bool) -> None:
    """The plan's RTZ, GeoJSON, JSON (and PNG over the forecast's wave height) in `out_dir`."""
    from ..io.files import write_plan_files

    hs = None
    if png:
        hs = (ensemble_hs_field_at(sampler, plan.departure_s)
              if isinstance(sampler, EnsembleCycle) else hs_field_at(sampler, plan.departure_s))
    write_plan_files(plan, Path(out_dir), forecast=hs, png=png)
