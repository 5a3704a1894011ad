"""Benchmark: every method vs the seed GA on Busan -> Long Beach, storm_march and calm_june.

13-day RTA, 4,600 TEU ship, departure 6 h after each scenario's forecast run. Per scenario and
method: tfoc_t, distance_nm, eta_minus_rta_h, land_crossings, compute_s; for the metaheuristics
repeated with different RNG seeds at an equal evaluation budget: mean_tfoc_t, std_tfoc_t; and
the seed GA's TFOC margin over the best two-stage (path + RPM schedule) method.
"""

from __future__ import annotations

import argparse
import json
import sys
import time

from ...cli.compare import ALL_METHODS, build_parser, run_compare

SCENARIOS = ("storm_march", "calm_june")


def _scenario_summary(doc: dict) -> dict:
    methods = {}
    for m in doc["methods"]:
        methods[m["method"]] = {k: m[k] for k in ("tfoc_t", "distance_nm", "eta_minus_rta_h",
                                                  "land_crossings", "compute_s", "feasible")}
    for row in doc.get("repeat", {}).get("rows", []):
        entry = methods.setdefault(row["method"], {})
        entry.update(mean_tfoc_t=row["mean_tfoc_t"], std_tfoc_t=row["std_tfoc_t"],
                     repeat_tfoc_t=row["tfoc_t"], repeat_feasible=row["feasible"])
    feasible = {k: v["tfoc_t"] for k, v in methods.items() if v.get("feasible")}
    lowest = min(feasible, key=lambda k: feasible[k]) if feasible else None
    return {
        "depart": doc["depart"], "rta": doc["rta"],
        "evaluations_per_metaheuristic": doc["evaluations_per_metaheuristic"],
        "methods": methods,
        "lowest_feasible_tfoc_method": lowest,
        "seed_ga_vs_best_two_stage": doc["seed_ga_vs_two_stage"],
        "best_known_tfoc_t": doc["best_known_tfoc_t"],
        "compute_s": doc["compute_s"],
    }


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="shiproute bench compare", description=__doc__.splitlines()[0])
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--evals", type=int, default=5000, help="route evaluations per metaheuristic")
    p.add_argument("--repeat", type=int, default=5, help="runs per metaheuristic (table 15)")
    p.add_argument("--scenarios", default=",".join(SCENARIOS))
    p.add_argument("--methods", default=",".join(ALL_METHODS))
    a = p.parse_args(argv)
    t0 = time.perf_counter()
    out: dict = {"benchmark": "compare", "route": "Busan -> Long Beach", "rta_days": 13,
                 "ship": "container_4600teu", "scenarios": {}}
    for name in a.scenarios.split(","):
        args = build_parser().parse_args(["--scenario", name, "--evals", str(a.evals), "--repeat",
                                     str(a.repeat), "--methods", a.methods])
        doc = run_compare(args)
        doc.pop("_tables", None)
        out["scenarios"][name] = _scenario_summary(doc)
    out["compute_s"] = round(time.perf_counter() - t0, 1)
    if a.json:
        print(json.dumps(out))
    else:
        print(json.dumps(out, indent=2))
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main(sys.argv[1:]))
