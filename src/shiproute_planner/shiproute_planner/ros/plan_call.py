"""One plan from the planner node's parameters: where the run starts, the `plan_voyage` call
and the plan's files."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

from ..plan_types import RoutePlan
from ..voyage_params import parse_utc
from .cycle_packer import hs_field_at
from .parameters import paths
from .replan_policy import at_departure_port


def plan_from_parameters(p: Callable[[str], Any], forecast: Any, *, cycle_id: str,
                         origin: str, depart_s: float, budget_s: float,
                         previous: RoutePlan | None,
                         position: tuple[float, float, float] | None,
                         progress: Callable[[Any], None], cancel: Any) -> RoutePlan:
    """Plan with the voyage, ship, method and data files named by the parameters (`p(name)`
    gives a parameter's value); the run's own inputs come as arguments."""
    from ..planning import plan_voyage

    pool = str(p("seed_pool_dir")) or None
    return plan_voyage(
        origin, str(p("destination")), depart_s, parse_utc(str(p("rta"))),
        str(p("ship")), forecast, cycle_id=cycle_id,
        objective=str(p("objective")), method=str(p("method")),
        budget_s=budget_s, seed=int(p("rng_seed")),
        stage_hours=float(p("stage_hours")), previous_plan=previous,
        position=position, seed_pool_dir=pool, progress=progress,
        cancel=cancel, ship_model=str(p("ship_model")),
        bathymetry=paths(str(p("bathymetry_files"))),
        default_bathymetry=bool(p("default_bathymetry")),
        ukc_margin_m=float(p("ukc_margin_m")),
        zones=paths(str(p("zones_files"))),
        clearance_nm=float(p("clearance_nm")),
        approaches_given=paths(str(p("approach_files"))),
    )


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

    hs = hs_field_at(sampler, plan.departure_s) if png else None
    write_plan_files(plan, Path(out_dir), forecast=hs, png=png)
