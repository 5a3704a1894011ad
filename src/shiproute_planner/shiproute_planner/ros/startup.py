"""What the planner node reads and states once at start: depth grids, the seed pool, and a
warm-up plan so the first real plan's budget is spent planning."""

from __future__ import annotations

import time
from collections.abc import Callable
from pathlib import Path
from typing import Any


def load_depth_grids(files: list[str], with_default: bool) -> str:
    """Read the depth grids now (they are cached per process), so the first plan's budget is
    spent planning; returns what was loaded, raises `PlannerError` for a bad grid."""
    from ..geo.depth import load_bathymetry

    bathy = load_bathymetry(files, with_default=with_default)
    return "depth: " + ("no bathymetry grid (depth not checked)" if bathy is None
                        else "bathymetry grids loaded")


def seed_pool_statement(directory: str) -> str:
    """What the persisted seed pool holds, so a restart visibly continues from it; raises
    whatever a damaged pool raises."""
    from ..ga.pool import POOL_FILE, SeedPool

    n = len(SeedPool(directory))
    return f"seed pool: {n} seed(s) in {Path(directory) / POOL_FILE}"


def warm_planner(p: Callable[[str], Any]) -> str:
    """Plan the voyage the parameters name once in calm water with no search (no generation,
    no baseline, no seed pool), before the first forecast cycle arrives: the compiled route
    kernels, the land and depth memory maps, the sea-lane graph and the coastline cells near
    the ports are then ready, and the first plan's clock does not pay for them (4-6 s
    against a 3 s budget without it). Returns what was warmed and how long it took; raises
    what planning the voyage raises (the caller reports it, the first plan says it too)."""
    from ..front import top_speed_s
    from ..geo.full_land import first_builds, first_builds_clause
    from ..planning import plan
    from ..request import PlanOptions
    from ..voyage_params import parse_utc
    from .plan_call import node_request

    built = first_builds()
    t0 = time.perf_counter()
    departure, rta_s = str(p("departure_time")), parse_utc(str(p("rta")))
    # without a departure time the voyage leaves early enough to be possible
    depart_s = parse_utc(departure) if departure else rta_s - 1.5 * top_speed_s(
        str(p("origin")), str(p("destination")), str(p("ship")), str(p("loading")))
    request = node_request(p, origin=str(p("origin")), depart_s=depart_s, rta_s=rta_s,
                           objective="", calls=())
    tiles = region_tiles(p, str(p("origin")), str(p("destination")))
    plan(request, PlanOptions(method=str(p("method")), budget_s=0.0, max_generations=0,
                              with_baseline=False, stage_hours=float(p("stage_hours")) or None),
         None)
    once = first_builds_clause(built)
    if tiles:
        once += f"; built {tiles} full-resolution coastline tiles of its region (once)"
    return (f"warm-up: {request.origin} -> {request.destination} set up in calm water in "
            f"{time.perf_counter() - t0:.1f} s (kernels, land and depth maps, sea lanes{once})")


def region_tiles(p: Callable[[str], Any], origin: str, destination: str) -> int:
    """Build the full-resolution coastline tiles of the region between the voyage's ports
    (`route.land_walk.REGION_MARGINS_DEG`; kept in the data directory, so only a machine's
    first start for a region pays, ~15 ms a tile): the first plan's search then reads them
    instead of building them. How many were new."""
    from ..geo.landmask import default_land_mask
    from ..geo.ports import resolve_port
    from ..route.clearance import ClearanceRule
    from ..route.land_walk import REGION_MARGINS_DEG, build_region_tiles

    land = default_land_mask()
    a, b = (resolve_port(name, land) for name in (origin, destination))
    rule = ClearanceRule(float(p("open_sea_clearance_nm")), float(p("approach_clearance_nm")),
                         float(p("approach_zone_nm")))
    return build_region_tiles((a.lon_deg, a.lat_deg), (b.lon_deg, b.lat_deg),
                              REGION_MARGINS_DEG, rule)


def warm_up_logged(p: Callable[[str], Any], logger: Any) -> None:
    """`warm_planner`, its outcome logged; a failure is a warning (the first plan then pays
    for the warm-up, and says so in its timing), never the end of the planning thread."""
    try:
        logger.info(warm_planner(p))
    except Exception as err:  # the voyage may be set later; the node keeps running
        logger.warning(f"warm-up skipped: {err}")
