"""`shiproute ship learn | drift | synth-records`: learn a ship model from records, watch drift."""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from ..errors import AisReplayError


def _forecasts(specs: Sequence[str]) -> list[Any]:
    from shiproute_planner.plan_setup import load_forecast

    return [load_forecast(s) for s in specs]


def prepare(paths: Sequence[str], forecast_specs: Sequence[str], ship: Any,
            forecasts: Sequence[Any] | None = None) -> tuple[dict, dict]:
    """Records -> met along the track -> ISO 19030 cleaning: (segment table, report)."""
    from .cleaning import CleaningConfig, clean
    from .records import join_met, read_records

    records = read_records(paths)
    fc = list(forecasts) if forecasts is not None else _forecasts(forecast_specs)
    met = join_met(records, fc)
    seg, report = clean(records, met, CleaningConfig(breadth_m=ship.hull.breadth_m))
    report["sources"] = list(records.sources)
    return seg, report


def _learn(args: argparse.Namespace) -> int:
    from shiproute_planner.learned.train import TrainConfig, train
    from shiproute_planner.ship import load_ship

    ship = load_ship(args.ship)
    seg, report = prepare(args.records, args.forecast, ship)
    cfg = TrainConfig(seed=args.seed, members=args.members)
    model = train(ship, seg, cfg, report)  # raises before anything is written
    model.save(args.out)
    print(json.dumps({"model": args.out, "ship": ship.name, "records": report["records_in"],
                      "clean_segments": report["clean_segments"],
                      "dropped_by_rule": report["dropped_by_rule"],
                      "rules_not_applied": report["rules_not_applied"],
                      **model.report["metrics"]}, indent=2))
    return 0


def _drift(args: argparse.Namespace) -> int:
    from shiproute_planner.learned.model import LearnedModel
    from shiproute_planner.learned.tables import learned_fast_model
    from shiproute_planner.ship import fast_model, load_ship

    from .drift import daily, drift_table, plot

    ship = load_ship(args.ship)
    learned = None
    if args.model == "physics":
        model = fast_model(ship)
    else:
        learned = LearnedModel.load(args.model)
        model = learned_fast_model(ship, learned, source=args.model)
    seg, report = prepare(args.records, args.forecast, ship)
    if seg["time_s"].size == 0:
        raise AisReplayError(f"no clean segments in the records ({report['dropped_by_rule']})")
    table = drift_table(seg, model, learned)
    summary = daily(table)
    out = {"model": args.model, "ship": ship.name, "clean_segments": int(seg["time_s"].size),
           **summary}
    if args.plot:
        plot(table, summary, args.plot, f"{ship.name}: performance vs {Path(args.model).name}")
        out["plot"] = args.plot
    print(json.dumps(out, indent=2))
    return 0


def _synth(args: argparse.Namespace) -> int:
    from shiproute_planner.ship import load_ship

    from .synth import HullChange, simulate_fleet_records, write_bag, write_csv

    ship = load_ship(args.ship)
    ds = _forecasts([args.forecast])[0]
    start = float(ds["time"].values[0].astype("datetime64[s]").astype(float)) + 3600.0
    rec = simulate_fleet_records(ship, ds, args.voyages, start, seed=args.seed,
                                 change=HullChange(friction_increase=args.fouling,
                                                   extra_trim_m=args.extra_trim_m))
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    write_csv(rec, out / "records.csv")
    counts = write_bag(rec, out / "records_bag")
    print(json.dumps({"records": len(rec), "csv": str(out / "records.csv"),
                      "bag": str(out / "records_bag"), "messages": counts}, indent=2))
    return 0


def build_parser() -> argparse.ArgumentParser:
    """Parser of the learning subcommands of `shiproute ship`."""
    ap = argparse.ArgumentParser(prog="shiproute ship", description=__doc__)
    sub = ap.add_subparsers(dest="cmd", required=True)
    lrn = sub.add_parser("learn", help="learn fuel-rate and RPM models from records")
    lrn.add_argument("records", nargs="+", help="ShipState bags (dir or .mcap) or CSV logs")
    lrn.add_argument("--forecast", nargs="+", required=True,
                     help="forecast/hindcast files or bundled scenarios covering the records")
    lrn.add_argument("--out", required=True, help="model file to write (.nc)")
    lrn.add_argument("--ship", default="container_4600teu", help="ship file the records are of")
    lrn.add_argument("--seed", type=int, default=0)
    lrn.add_argument("--members", type=int, default=5, help="networks per ensemble")
    dr = sub.add_parser("drift", help="ISO 19030 performance indicator of records vs a model")
    dr.add_argument("records", nargs="+")
    dr.add_argument("--model", required=True, help="learned model .nc, or 'physics'")
    dr.add_argument("--forecast", nargs="+", required=True)
    dr.add_argument("--ship", default="container_4600teu")
    dr.add_argument("--plot", default=None, help="PNG of the indicator over time")
    sy = sub.add_parser("synth-records",
                        help="records (bag + CSV) of a fouled, re-trimmed ship (test data)")
    sy.add_argument("out", help="output directory")
    sy.add_argument("--forecast", default="storm_march")
    sy.add_argument("--ship", default="container_4600teu")
    sy.add_argument("--voyages", type=int, default=5)
    sy.add_argument("--fouling", type=float, default=0.15, help="frictional resistance increase")
    sy.add_argument("--extra-trim-m", type=float, default=1.5)
    sy.add_argument("--seed", type=int, default=0)
    return ap


def main(argv: list[str]) -> int:
    """Entry point (called by `shiproute ship` for learn, drift and synth-records)."""
    from shiproute_planner.errors import PlannerError
    from shiproute_planner.ship import ShipModelError

    args = build_parser().parse_args(argv)
    try:
        return {"learn": _learn, "drift": _drift, "synth-records": _synth}[args.cmd](args)
    except (AisReplayError, ShipModelError, PlannerError, OSError) as exc:
        print(f"shiproute ship {args.cmd}: error: {exc}", file=sys.stderr)
        return 2


