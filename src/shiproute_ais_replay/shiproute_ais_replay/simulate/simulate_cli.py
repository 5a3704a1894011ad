"""``shiproute bag simulate``: plan (RTZ / plan JSON) or great circle + forecast -> voyage bag."""

from __future__ import annotations

import argparse
import json
import math
import time
from typing import Any

from ..ais.ais_nmea import parse_time_ns
from ..errors import SimulationError

DEFAULT_SHIP = "container_4600teu"


def add_simulate_parser(sub: Any) -> None:
    """Register the ``simulate`` sub-command on an argparse sub-parser collection."""
    p = sub.add_parser("simulate", help="sail a plan through a forecast with the ship model")
    p.add_argument("output", help="bag directory (or .mcap file) to create")
    p.add_argument("--plan", help="RTZ route with schedule, or planner plan JSON")
    p.add_argument("--from-lat", type=float)
    p.add_argument("--from-lon", type=float)
    p.add_argument("--to-lat", type=float)
    p.add_argument("--to-lon", type=float)
    p.add_argument("--depart", help="departure time, ISO 8601 UTC (default: from the plan)")
    p.add_argument("--rpm", type=float, default=math.nan,
                   help="shaft rpm for legs without rpm/speed/eta (required for great circle)")
    p.add_argument("--forecast", default="",
                   help="forecast NetCDF/GRIB file or bundled scenario name (default: calm)")
    p.add_argument("--ship", default="",
                   help=f"bundled ship name or ship file (default {DEFAULT_SHIP})")
    p.add_argument("--rate-hz", type=float, default=1.0, help="ShipState output rate")
    p.add_argument("--model-step-s", type=float, default=600.0,
                   help="ship-model evaluation step")
    p.add_argument("--seed", type=int, default=0, help="seed of the sensor noise")
    p.add_argument("--no-noise", action="store_true", help="exact model values")
    p.add_argument("--mmsi", type=int, default=0)
    p.add_argument("--no-fix", action="store_true", help="do not write NavSatFix")
    p.set_defaults(func=cmd_simulate)


def default_ship(names: list[str]) -> str:
    """The demo ship (4,600 TEU container ship) when bundled, else the first bundled ship."""
    return DEFAULT_SHIP if DEFAULT_SHIP in names else names[0]


def forecast_sampler(spec: str) -> Any:
    """Sampler function of a forecast file or bundled scenario name; None for calm water."""
    if not spec:
        return None
    from shiproute_weather.ingest.loaders import open_forecast
    from shiproute_weather.sampling.sampler import ForecastSampler
    from shiproute_weather.scenarios.catalogue import scenario_dataset, scenario_names

    ds = scenario_dataset(spec) if spec in scenario_names() else open_forecast([spec])
    return ForecastSampler(ds).sample


def cmd_simulate(args: argparse.Namespace) -> int:
    """Simulate and write the voyage; prints a JSON summary."""
    from shiproute_planner.ship import PhysicsModel, bundled_ships, load_ship

    from ..bag.statebag import write_states
    from .simulator import SimulationOptions, VoyageSimulator
    from .voyage_input import great_circle, read_voyage

    if args.plan:
        plan = read_voyage(args.plan)
    elif None not in (args.from_lat, args.from_lon, args.to_lat, args.to_lon):
        plan = great_circle(args.from_lat, args.from_lon, args.to_lat, args.to_lon, args.rpm)
    else:
        raise SimulationError("give --plan FILE or all of --from-lat/--from-lon/--to-lat/--to-lon")
    depart_s = plan.departure_s
    if args.depart:
        t_ns = parse_time_ns(args.depart)
        if t_ns is None:
            raise SimulationError(f"--depart {args.depart!r} is not an ISO 8601 time")
        depart_s = t_ns / 1e9
    ship = load_ship(args.ship or plan.ship or default_ship(bundled_ships()))
    opts = SimulationOptions(departure_s=depart_s, rate_hz=args.rate_hz,
                             model_step_s=args.model_step_s, default_rpm=args.rpm,
                             noise=not args.no_noise, seed=args.seed, mmsi=args.mmsi)
    sim = VoyageSimulator(plan, PhysicsModel(ship), ship, opts, forecast_sampler(args.forecast))
    t0 = time.monotonic()
    counts = write_states(sim.states(), args.output, with_fix=not args.no_fix)
    s = sim.summary
    print(json.dumps({
        "output": args.output, "ship": ship.name, "forecast": args.forecast or "calm",
        "arrived": s.arrived, "duration_h": s.duration_s / 3600.0,
        "distance_nm": s.distance_nm, "fuel_t": s.fuel_t, "states": s.states,
        "messages_written": counts, "wall_s": time.monotonic() - t0,
    }, indent=2))
    return 0
