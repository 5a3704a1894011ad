"""Plan a fleet on Dask: voyages file (CSV/YAML) x forecasts -> per-voyage files + a summary."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..errors import PlannerError


def build_parser() -> argparse.ArgumentParser:
    """Argument parser of `shiproute fleet`."""
    ap = argparse.ArgumentParser(
        prog="shiproute fleet", description=__doc__,
        epilog="Columns: vessel, from, to, depart, rta|window (required); voyage, ship, via, "
               "objective, model, method, budget, seed, stage_hours, forecast (optional). "
               "depart may be START/END/STEP; window EARLIEST/LATEST[/STEP].")
    ap.add_argument("voyages", help="voyages file (.csv or .yaml)")
    ap.add_argument("--forecast", nargs="+", default=[], metavar="F",
                    help="forecast file, files of one cycle joined with '+', or bundled "
                         "scenario; several = each voyage on each (unless its row names one)")
    ap.add_argument("--scheduler", default=None, metavar="ADDRESS",
                    help="address of a running Dask scheduler (tcp://host:8786); default: a "
                         "LocalCluster on this machine")
    ap.add_argument("--connect-timeout", type=float, default=10.0, metavar="S",
                    help="seconds to wait for --scheduler to answer (default 10)")
    ap.add_argument("--workers", type=int, default=2,
                    help="worker processes of the LocalCluster (default 2)")
    ap.add_argument("--out", default="fleet_out", help="output directory")
    ap.add_argument("--budget", default="3s",
                    help="default budget of rows without one: 3s (wall) or 4000ev (evaluations)")
    ap.add_argument("--seed-pool", default=None,
                    help="seed pool directory shared by the workers (on a multi-host cluster it "
                         "must be on a shared file system)")
    ap.add_argument("--png", action="store_true", help="also a PNG per voyage")
    ap.add_argument("--force", action="store_true",
                    help="re-plan voyages already planned from the same inputs")
    ap.add_argument("--retries", type=int, default=2, help="Dask retries of a failing task")
    ap.add_argument("--quiet", action="store_true", help="no progress bar")
    ap.add_argument("--make-example", type=int, default=0, metavar="N",
                    help="write the example voyages file (N voyages from the world lanes and "
                         "the bundled scenarios) to VOYAGES and exit")
    return ap


def main(argv: list[str]) -> int:
    """Entry point of `shiproute fleet`: 0 all planned and feasible, 1 some infeasible, failed
    or skipped, 2 bad arguments, unreadable voyages file or unreachable scheduler."""
    args = build_parser().parse_args(argv)
    if args.workers < 1:
        print("shiproute fleet: error: --workers must be >= 1", file=sys.stderr)
        return 2
    if args.make_example:
        from ..fleet.example import example_csv

        Path(args.voyages).write_text(example_csv(args.make_example))
        print(f"wrote {args.make_example} voyages to {args.voyages}")
        return 0
    from ..fleet import runner, summary
    from ..fleet import voyages as voyages_mod
    from ..plan_request import Budget

    try:
        Budget.parse(args.budget)
        table = voyages_mod.read_voyages(args.voyages, default_budget=args.budget)
        for e in table.errors:
            print(f"{args.voyages}:{e.line}: {e.voyage}: skipped: {e.reason}", file=sys.stderr)
        opts = runner.FleetOptions(
            out_dir=args.out, forecasts=tuple(args.forecast), scheduler=args.scheduler,
            workers=args.workers, seed_pool_dir=args.seed_pool, png=args.png,
            retries=args.retries, connect_timeout_s=args.connect_timeout)
        run = runner.run_fleet(table.voyages, opts, force=args.force,
                               show_progress=not args.quiet)
    except PlannerError as exc:
        print(f"shiproute fleet: error: {exc}", file=sys.stderr)
        return 2
    records = run.records + summary.skipped_records(list(table.errors))
    summary.mark_best_candidates(records)
    files = summary.write_summary(records, args.out)
    for r in records:
        if r.get("status") == "failed":
            print(f"{r.get('voyage_id')}: failed: {r.get('reason')}", file=sys.stderr)
    print(format_fleet(records, run))
    print("summary: " + ", ".join(str(p) for p in files.values()))
    print(f"voyage files: {Path(args.out) / 'voyages'}/<voyage>--<input hash>/plan.*")
    bad = any(r.get("status") != "planned" or not r.get("feasible") for r in records)
    return 1 if bad else 0


def format_fleet(records: list[dict], run) -> str:
    """Totals of a batch."""
    from ..fleet import summary

    planned = [r for r in records if r.get("status") == "planned"]
    fresh = [r for r in planned if not r.get("already_planned")]
    fuel = sum(float(r.get("fuel_t") or 0.0) for r in planned)
    both = [r for r in planned if summary.comparable(r)]
    saved = sum(float(r["fuel_saved_t"]) for r in both)
    base = sum(float(r["baseline_fuel_t"]) for r in both)
    late = sum(1 for r in planned if float(r.get("eta_margin_h") or 0.0) < -0.01)
    lines = [
        f"voyages   {len(records)}: planned {len(fresh)}, already planned "
        f"{len(planned) - len(fresh)}, failed "
        f"{sum(1 for r in records if r.get('status') == 'failed')}, invalid rows "
        f"{sum(1 for r in records if r.get('status') == 'invalid')}",
        f"fuel      {fuel:.1f} t planned; {saved:.1f} t saved against constant RPM "
        f"({100 * saved / base if base else 0.0:.1f} %) on the {len(both)} voyages where plan "
        "and baseline are feasible",
        f"flags     {sum(1 for r in planned if not r.get('feasible'))} infeasible, "
        f"{late} late",
    ]
    if run.cluster:
        lines.append(f"cluster   {run.cluster}: start + worker set-up {run.start_s:.1f} s, "
                     f"planning {run.wall_s:.1f} s")
    return "\n".join(lines)
