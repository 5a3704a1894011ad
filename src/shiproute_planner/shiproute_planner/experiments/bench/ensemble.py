"""Ensemble benchmark: Busan -> Long Beach, 13-day RTA, 4,600 TEU, on the 20-member
`storm_march_ensemble` scenario.

Plans once on every member with a risk measure (default cvar:0.9, P(Hs > limit) <= 0.1,
P(late) <= 0.5: late being a delay even MCR cannot make up) and once on the members' mean
forecast alone; both plans are then sailed on the same members (the plan's `ensemble`
block), with heave-to above the ship's wave limit and the fuel to still meet the RTA
(`route.heavy_seas`). Reports the cold plan time of the risk-aware plan (the sampler is
packed before the timing, `load_and_pack_s`; land mask, sea lanes and the first use of the
kernels are inside it, as for a first plan), its P90 fuel and P(Hs > limit), the same of
the mean plan, how often each heaves to, the process's peak RSS and the 16-bit packed wire
size of the whole cycle (`shiproute_weather.wire.packing`: codes + offset and scale per
field and valid time).
"""

from __future__ import annotations

import argparse
import resource
import time
from datetime import timedelta
from pathlib import Path

import numpy as np
from shiproute_core.bench_report import print_figures

DEPART = "2026-03-03T18:00Z"
SCENARIO = "storm_march_ensemble"
FIELD_HEADER_BYTES = 16  # add_offset and scale_factor (float64 each) per packed field


def cycle_bytes(ds) -> int:
    """Bytes of every member's fields in 16-bit simple packing, slice by slice."""
    from shiproute_weather.contract.canonical import present_variables
    from shiproute_weather.wire.packing import pack_field

    total = 0
    for name in present_variables(ds):
        values = ds[name].transpose("member", "time", "latitude", "longitude").values
        for member in values:
            for field in member:
                total += pack_field(field, name).nbytes + FIELD_HEADER_BYTES
    return total


def run(budget_s: float, risk: str, p_hs_max: float, p_late_max: float, seed: int) -> dict:
    """Run the benchmark and return its JSON-able result."""
    from shiproute_weather.scenarios.catalogue import scenario_dataset, scenario_path

    from ...planning import plan_voyage

    t = time.perf_counter()
    path = scenario_path(SCENARIO)
    scenario_s = time.perf_counter() - t
    t = time.perf_counter()
    ds = scenario_dataset(SCENARIO)
    from shiproute_weather.sampling.sampler import ForecastSampler

    sampler = ForecastSampler(ds, dtype=np.float16)
    members = ds.sizes["member"]
    wire = cycle_bytes(ds)
    del ds
    load_s = time.perf_counter() - t
    common: dict = dict(ship="container_4600teu", seed=seed, default_bathymetry=True,
                        budget_s=budget_s)
    t = time.perf_counter()
    plan = plan_voyage("Busan", "Long Beach", DEPART, timedelta(days=13), forecast=sampler,
                       risk=risk, p_hs_max=p_hs_max, p_late_max=p_late_max, **common)
    plan_s = time.perf_counter() - t
    mean_plan = plan_voyage("Busan", "Long Beach", DEPART, timedelta(days=13),
                            forecast=sampler, **common)
    ens, ens_mean = plan.extra.get("ensemble") or {}, mean_plan.extra.get("ensemble") or {}
    if not ens or not ens_mean:
        raise SystemExit("a plan has no ensemble statement: " + "; ".join(
            w for w in (*plan.warnings, *mean_plan.warnings) if "ensemble" in w))
    return {
        "members": members,
        "risk": risk, "p_hs_max": p_hs_max, "p_late_max": p_late_max, "budget_s": budget_s,
        "plan_s": round(plan_s, 3),
        "p90_fuel_t": round(ens["fuel_t"]["p90"], 2),
        "p_hs_violation": round(ens["p_hs_violation"], 3),
        "p_late": round(ens["p_late"], 3),
        "mean_fuel_t": round(ens["fuel_t"]["mean"], 2),
        "mean_plan_p90_fuel_t": round(ens_mean["fuel_t"]["p90"], 2),
        "mean_plan_p_hs_violation": round(ens_mean["p_hs_violation"], 3),
        "mean_plan_p_late": round(ens_mean["p_late"], 3),
        "mean_plan_mean_fuel_t": round(ens_mean["fuel_t"]["mean"], 2),
        "p_heave_to": round(ens["heavy_seas"]["p_heave_to"], 3),
        "mean_plan_p_heave_to": round(ens_mean["heavy_seas"]["p_heave_to"], 3),
        "heavy_seas_model": ens["heavy_seas"]["model"],
        "risk_tradeoff": [w for w in plan.warnings if w.startswith("risk trade-off")],
        "generations": plan.generations, "evaluations": plan.evaluations,
        "planner_rss_mb": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, 1),
        "cycle_bytes": wire,
        "scenario_file_mb": round(Path(path).stat().st_size / 1e6, 1),
        "scenario_build_or_find_s": round(scenario_s, 2),
        "load_and_pack_s": round(load_s, 2),
    }


def main(argv: list[str]) -> int:
    """`shiproute bench ensemble [--json] [--budget S] [--risk M] [--p-hs-max P] ...`."""
    ap = argparse.ArgumentParser(prog="shiproute bench ensemble", description=__doc__)
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    ap.add_argument("--budget", type=float, default=8.0)
    ap.add_argument("--risk", default="cvar:0.9")
    ap.add_argument("--p-hs-max", type=float, default=0.1)
    ap.add_argument("--p-late-max", type=float, default=0.5)
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args(argv)
    result = run(args.budget, args.risk, args.p_hs_max, args.p_late_max, args.seed)
    print_figures(result, args.json)
    return 0
