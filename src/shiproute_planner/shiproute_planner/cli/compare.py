"""Compare the seed GA with the baseline methods on one voyage (tables 11/12, 15, plots, JSON).

Every method plans the same voyage with the same ship model, forecast, land mask and
constraints; metaheuristics get an equal number of route evaluations. Prints the table in the
shape of the reference study's tables 11/12 (and table 15 with --repeat N), and with --out
writes compare.json, compare.png (routes over the wave field, RPM and speed profiles) and
pareto.png (3DDP and NSGA-II ETA-fuel fronts).
"""

from __future__ import annotations

import argparse
import json
import re
import sys
import time
from datetime import UTC, datetime
from pathlib import Path

from ..baselines.metaheuristics import seed_genes
from ..errors import PlannerError
from ..experiments.compare import (
    GRAPH_ORDER,
    META_ORDER,
    REPEAT_ORDER,
    CompareSettings,
    best_known_t,
    repeat_runs,
    run_methods,
    seed_ga_margin_pct,
)
from ..experiments.outcome import comparison_table, repeat_table
from ..experiments.plots import plot_comparison, plot_pareto
from ..experiments.voyage import build_inputs, default_departure_s, load_forecast
from ..request import PlanOptions, VoyageRequest

ALL_METHODS = (*GRAPH_ORDER, *META_ORDER)


def parse_rta(text: str, depart_s: float) -> float:
    """'13d', '312h', '90m' after departure, or an ISO 8601 UTC time -> POSIX s."""
    m = re.fullmatch(r"\s*(\d+(?:\.\d+)?)\s*([dhm])\s*", text)
    if m:
        scale = {"d": 86400.0, "h": 3600.0, "m": 60.0}[m.group(2)]
        return depart_s + float(m.group(1)) * scale
    return datetime.fromisoformat(text.strip().replace("Z", "+00:00")).timestamp()


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="shiproute compare", description=__doc__.splitlines()[0])
    p.add_argument("--scenario", default="storm_march",
                   help="bundled scenario name or forecast file (default storm_march)")
    p.add_argument("--from", dest="origin", default="Busan")
    p.add_argument("--to", dest="destination", default="Long Beach")
    p.add_argument("--depart", default=None,
                   help="ISO 8601 UTC (default: forecast reference time + 6 h)")
    p.add_argument("--rta", default="13d", help="duration (13d, 312h) or ISO time (default 13d)")
    p.add_argument("--ship", default="container_4600teu")
    p.add_argument("--methods", default=",".join(ALL_METHODS),
                   help="comma-separated methods (default: all)")
    p.add_argument("--evals", type=int, default=6000,
                   help="route evaluations per metaheuristic run (default 6000)")
    p.add_argument("--repeat", type=int, default=0,
                   help="table 15: runs per metaheuristic with different RNG seeds")
    p.add_argument("--seed", type=int, default=0, help="first RNG seed")
    p.add_argument("--out", type=Path, default=None, help="directory for JSON and PNGs")
    p.add_argument("--json", action="store_true", help="print JSON instead of tables")
    return p


def _log(msg: str) -> None:
    print(msg, file=sys.stderr, flush=True)


def run_compare(args: argparse.Namespace) -> dict:
    """Run the comparison described by parsed arguments; returns the JSON document."""
    ds = load_forecast(args.scenario)
    depart_s = (datetime.fromisoformat(args.depart.replace("Z", "+00:00")).timestamp()
                if args.depart else default_departure_s(ds))
    rta_s = parse_rta(args.rta, depart_s)
    inp = build_inputs(VoyageRequest(args.origin, args.destination, depart_s, rta_s, args.ship),
                       PlanOptions(stage_hours=12.0), ds)
    methods = [m.strip() for m in args.methods.split(",") if m.strip()]
    unknown = sorted(set(methods) - set(ALL_METHODS))
    if unknown:
        raise PlannerError(f"unknown methods {unknown}; choose from {', '.join(ALL_METHODS)}")
    t0 = time.perf_counter()
    inp = type(inp)(inp.problem, inp.env, inp.land, seed_genes=seed_genes(inp))
    settings = CompareSettings(evaluations=args.evals)
    _log(f"comparing {len(methods)} methods, {args.evals} evaluations per metaheuristic")
    outcomes = run_methods(inp, methods, settings, args.seed, on_done=lambda o: _log(
        f"  {o.label:<28} {o.tfoc_t:8.1f} t  {o.compute_s:6.1f} s"))
    rows = []
    if args.repeat > 0:
        rep = [m for m in REPEAT_ORDER if m in methods] or list(REPEAT_ORDER)
        _log(f"table 15: {len(rep)} algorithms x {args.repeat} runs")
        rows = repeat_runs(inp, rep, settings, args.repeat, args.seed, on_done=lambda r: _log(
            f"  {r.label:<20} mean {r.mean_tfoc_t:8.1f} t  std {r.std_tfoc_t:6.1f} t"))
    best = best_known_t(outcomes, rows)
    p = inp.problem
    doc = {
        "scenario": args.scenario,
        "from": p.dep_name, "to": p.arr_name,
        "depart": datetime.fromtimestamp(p.depart_s, UTC).isoformat(),
        "rta": datetime.fromtimestamp(p.rta_s, UTC).isoformat(),
        "ship": args.ship,
        "evaluations_per_metaheuristic": args.evals,
        "methods": [o.as_json() for o in outcomes],
        "seed_ga_vs_two_stage": seed_ga_margin_pct(outcomes),
        "best_known_tfoc_t": round(best, 3),
        "compute_s": round(time.perf_counter() - t0, 2),
    }
    if rows:
        doc["repeat"] = {"runs": args.repeat, "rows": [r.as_json(best) for r in rows]}
    if args.out is not None:
        args.out.mkdir(parents=True, exist_ok=True)
        title = f"{p.dep_name} -> {p.arr_name}, {args.scenario}"
        doc["files"] = {"png": str(plot_comparison(outcomes, args.out / "compare.png", ds, title))}
        pareto = plot_pareto(outcomes, args.out / "pareto.png")
        if pareto is not None:
            doc["files"]["pareto_png"] = str(pareto)
        doc["files"]["json"] = str(args.out / "compare.json")
        (args.out / "compare.json").write_text(json.dumps(doc, indent=2))
    doc["_tables"] = (comparison_table(outcomes), repeat_table(rows, best) if rows else "")
    return doc


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    try:
        doc = run_compare(args)
    except (PlannerError, ValueError, OSError) as exc:
        _log(f"shiproute compare: {exc}")
        return 2
    tables = doc.pop("_tables")
    if args.json:
        print(json.dumps(doc, indent=2))
    else:
        print(tables[0])
        if tables[1]:
            print()
            print(tables[1])
        margin = doc["seed_ga_vs_two_stage"]
        if margin:
            print(f"\nseed GA vs best two-stage ({margin['best_two_stage']}): "
                  f"{margin['seed_ga_margin_pct']:+.2f} % TFOC saving")
        for k, v in doc.get("files", {}).items():
            print(f"{k}: {v}")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main(sys.argv[1:]))
