"""Data of the end-to-end demo, made once and cached: forecast scenarios and the voyage bag.

The recorded voyage is what a ship of the bundled 4,600 TEU class sails from Busan to Long Beach
in the March storm scenario on the constant-RPM sea-lane/great-circle baseline that meets the
13-day RTA; `shiproute bag simulate` writes it from that plan with the same ship model.
"""

from __future__ import annotations

import dataclasses
import os
import time
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from shiproute_planner.request import VoyageRequest

ORIGIN = "Busan"
DESTINATION = "Long Beach"
DEPARTURE = "2026-03-03T18:00:00Z"
RTA = "2026-03-16T18:00:00Z"
SHIP = "container_4600teu"
FIRST_CYCLE = "storm_march"
SECOND_CYCLE = "storm_march_cycle2"
STATE_RATE_HZ = 1.0 / 60.0  # one ShipState a minute: 18,720 messages for 13 days


@dataclass(frozen=True)
class DemoData:
    """Paths of the demo's inputs."""

    first_forecast: Path
    second_forecast: Path
    voyage_bag: Path
    seed_pool_dir: Path


def data_dir() -> Path:
    """The workspace data directory ($SHIPROUTE_DATA_DIR, else ~/.cache/shiproute)."""
    root = os.environ.get("SHIPROUTE_DATA_DIR") or str(Path.home() / ".cache" / "shiproute")
    return Path(root)


def _voyage() -> VoyageRequest:
    """The demo voyage as the planner's request."""
    from shiproute_planner.request import VoyageRequest, voyage_times

    return VoyageRequest(ORIGIN, DESTINATION, *voyage_times(DEPARTURE, RTA), SHIP)


def _voyage_bag(path: Path, log) -> Path:
    """Plan the constant-RPM baseline and simulate the voyage along it (skipped when cached)."""
    if (path / "metadata.yaml").exists():
        return path
    from shiproute_ais_replay.cli import main as bag_main
    from shiproute_planner.io.files import write_plan_files
    from shiproute_planner.planning import plan
    from shiproute_planner.request import PlanOptions
    from shiproute_weather.scenarios.catalogue import scenario_dataset

    log(f"making the demo voyage bag {path} (once)")
    forecast = scenario_dataset(FIRST_CYCLE)
    baseline = plan(_voyage(), PlanOptions(method="great_circle", budget_s=5.0,
                                           with_baseline=False), forecast)
    plan_dir = path.parent / "demo_voyage_plan"
    files = write_plan_files(baseline, plan_dir, forecast=forecast, png=False)
    tmp = path.with_name(path.name + ".tmp")
    bag_main(["simulate", str(tmp), "--plan", str(files["json"]), "--forecast", FIRST_CYCLE,
                   "--ship", SHIP, "--rate-hz", str(STATE_RATE_HZ), "--model-step-s", "1800"])
    tmp.rename(path)
    return path


REPLAN_AFTER_H = 20.0  # the warm-up's re-plan: the ship this far along the first plan


def _warm_up(log) -> None:
    """Compile (numba caches on disk, so only the first time or after a code change is slow)
    every kernel the nodes use, for the half-precision forecast storage the planner node
    keeps, and resolve the coastal cells and full-resolution distance tiles of the voyage's
    region (kept in the data directory), so a node's first plan is timed as a plan, not as
    compilation and polygon tests."""
    import numpy as np
    from shiproute_planner.geo.landmask import default_land_mask
    from shiproute_planner.geo.ports import resolve_port
    from shiproute_planner.plan_position import position_after
    from shiproute_planner.planning import plan
    from shiproute_planner.request import PlanOptions
    from shiproute_planner.route.clearance import DEFAULT_CLEARANCE
    from shiproute_planner.route.land_walk import REGION_MARGINS_DEG, build_region_tiles
    from shiproute_weather.sampling.sampler import ForecastSampler
    from shiproute_weather.scenarios.catalogue import scenario_dataset

    log("warming the planner's compiled kernels and the voyage region's coastline")
    land = default_land_mask()
    a, b = (resolve_port(p, land) for p in (ORIGIN, DESTINATION))
    land.fine_coast.resolve_voyage((a.lon_deg, a.lat_deg), (b.lon_deg, b.lat_deg),
                                   REGION_MARGINS_DEG)
    # the search's full-resolution tiles of the coasts its seeds reach (the great circles
    # via points 12 deg off it reach the Aleutians, Alaska and Hawaii; ~2,100 tiles, 30-40 s
    # once per machine): the node's first plan then searches instead of building them
    t0 = time.perf_counter()
    built = build_region_tiles((a.lon_deg, a.lat_deg), (b.lon_deg, b.lat_deg),
                               REGION_MARGINS_DEG, DEFAULT_CLEARANCE)
    if built:
        log(f"built {built} full-resolution coastline tiles of the voyage's region in "
            f"{time.perf_counter() - t0:.0f} s (once per machine)")
    forecast = ForecastSampler(scenario_dataset(FIRST_CYCLE), dtype=np.float16)
    voyage = dataclasses.replace(_voyage(), default_bathymetry=True)
    # the global depth grid's cache, as the node uses it, and the tiles a storm search meets
    first = plan(voyage, PlanOptions(budget_s=3.0, land=land), forecast)
    # a re-plan under way, as on the demo's second cycle: its kernel variants (previous plan,
    # ship's position) compiled in the node cost a first re-plan ~7 s after a source change
    plan(voyage, PlanOptions(budget_s=1.0, land=land, previous_plan=first,
                             position=position_after(first, REPLAN_AFTER_H)), forecast)
    # the calm-water kernels of the node's own warm-up (`ros.startup.warm_planner`): compiled
    # there they held the node ~60 s after a source change while the demo's clock ran
    plan(voyage, PlanOptions(budget_s=0.0, max_generations=0, with_baseline=False, land=land),
         None)


def prepare(log=print) -> DemoData:
    """Build (or reuse) the scenario files and the voyage bag; warm the compiled kernels."""
    from shiproute_weather.scenarios.catalogue import scenario_path

    root = data_dir()
    first = scenario_path(FIRST_CYCLE)
    second = scenario_path(SECOND_CYCLE)
    bag = _voyage_bag(root / "demo" / "busan_long_beach_march_voyage", log)
    _warm_up(log)
    return DemoData(first, second, bag, root / "seed_pool")
