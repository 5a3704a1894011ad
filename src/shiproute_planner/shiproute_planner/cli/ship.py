"""Ship files: list bundled ships, show one, export its performance profile (NetCDF)."""

from __future__ import annotations

import argparse
import dataclasses
import json

from ..ship import ShipModelError, bundled_ships, fast_model, load_ship
from ..ship.physics import PhysicsModel
from ..ship.profile import ProfileGrid, export_profile

LEARNING = {
    "learn": "learn fuel-rate and RPM models from records: RECORDS... --forecast F... --out M.nc",
    "drift": "ISO 19030 performance indicator of records vs a model: RECORDS... --model M.nc",
    "synth-records": "records (bag + CSV) of a fouled, re-trimmed ship for tests: OUT_DIR",
}
# Records live in the replay package (bags, simulation), which depends on this one: its
# `ship` subcommands are found through this entry-point group, never imported by name.
SHIP_COMMANDS_GROUP = "shiproute.ship_commands"


def _learning_main(name: str):
    """The `main(argv)` registered for a records subcommand, or None when none is installed."""
    from importlib.metadata import entry_points

    for ep in entry_points(group=SHIP_COMMANDS_GROUP, name=name):
        return ep.load()
    return None


def main(argv: list[str]) -> int:
    """``shiproute ship list | show NAME | profile NAME OUT.nc | learn | drift | synth-records``."""
    if argv and argv[0] in LEARNING:
        learning_main = _learning_main(argv[0])
        if learning_main is None:
            print(f"shiproute ship {argv[0]}: needs the shiproute_ais_replay package")
            return 2
        return learning_main(argv)
    ap = argparse.ArgumentParser(prog="shiproute ship", description=__doc__)
    sub = ap.add_subparsers(dest="cmd", required=True)
    sub.add_parser("list", help="bundled ship names")
    show = sub.add_parser("show", help="print a resolved ship file as JSON")
    show.add_argument("name", help="bundled name or path to a YAML ship file")
    show.add_argument("--condition", default=None)
    prof = sub.add_parser("profile", help="export the performance profile as NetCDF")
    prof.add_argument("name")
    prof.add_argument("out", help="output .nc path")
    prof.add_argument("--condition", default=None)
    prof.add_argument("--n-rpm", type=int, default=12)
    prof.add_argument("--model", choices=("fast", "physics"), default="fast",
                      help="fast (tables, < 0.5 %% from physics) or the direct physics solve")
    for name, text in LEARNING.items():
        sub.add_parser(name, help=text, add_help=False)
    args = ap.parse_args(argv)
    try:
        if args.cmd == "list":
            for name in bundled_ships():
                print(name)
            return 0
        ship = load_ship(args.name, args.condition)
        if args.cmd == "show":
            print(json.dumps(dataclasses.asdict(ship), indent=2))
            return 0
        model = fast_model(ship) if args.model == "fast" else PhysicsModel(ship)
        ds = export_profile(model, args.out, ProfileGrid.for_ship(ship, args.n_rpm))
        print(f"wrote {args.out}: {dict(ds.sizes)}")
        return 0
    except (ShipModelError, OSError) as exc:
        print(f"shiproute ship: error: {exc}")
        return 2
