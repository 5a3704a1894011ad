"""Time-fuel front benchmark: a 9-point front on Busan -> Long Beach, 13-day latest arrival,
4,600 TEU, storm_march (the planner bench's voyage). Reports the front's plans (voyage hours,
fuel, feasibility), whether it is monotone, and its wall time; the forecast sampler, land mask
and compiled kernels are warmed before timing, as in a running planner."""

from __future__ import annotations

import argparse
import dataclasses
import time
from typing import Any

import numpy as np
from shiproute_core.bench_report import print_figures

from ...front import plan_front
from ...geo.landmask import default_land_mask
from ...plan_request import build_request
from ...planning import plan
from ...request import PlanOptions

DEPART = "2026-03-03T18:00Z"


def front_bench(points: int = 9, budget_s: float = 9.0, seed: int = 0) -> dict[str, Any]:
    """`front_points` (ETA/fuel per plan), `front_s` (wall time of the whole front) and
    details for the bundled storm voyage."""
    from shiproute_weather.sampling.sampler import ForecastSampler
    from shiproute_weather.scenarios.catalogue import scenario_dataset

    land = default_land_mask()
    sampler = ForecastSampler(scenario_dataset("storm_march"), dtype=np.float16)
    req = build_request(origin="Busan", destination="Long Beach", depart=DEPART, rta="13d",
                        objective="front", budget=f"{budget_s:g}s", seed=seed,
                        front_points=points)
    warm_up = PlanOptions(budget_s=0.0, max_generations=0, with_baseline=False, land=land)
    plan(dataclasses.replace(req.voyage_request(), default_bathymetry=True, objective="fuel"),
         warm_up,
         sampler)  # sea lanes, coastline, kernels
    t = time.perf_counter()
    front = plan_front(req, sampler, land=land, default_bathymetry=True)
    front_s = time.perf_counter() - t
    return {
        "front_points": len(front.plans),
        "front_s": round(front_s, 3),
        "front_monotone": front.monotone,
        "front_ends_feasible": bool(front.plans[0].feasible and front.plans[-1].feasible),
        "front_hours": [round(p.total_time_s / 3600.0, 2) for p in front.plans],
        "front_fuel_t": [round(p.total_fuel_t, 2) for p in front.plans],
        "front_feasible": [p.feasible for p in front.plans],
        "front_reasons": ["; ".join(p.infeasible_reasons) for p in front.plans],
        "front_notes": list(front.notes),
    }


def main(argv: list[str]) -> int:
    """`shiproute bench front [--json] [--points N] [--budget S] [--seed K]`."""
    ap = argparse.ArgumentParser(prog="shiproute bench front", description=__doc__)
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    ap.add_argument("--points", type=int, default=9)
    ap.add_argument("--budget", type=float, default=9.0, help="wall time of the whole front")
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args(argv)
    result = front_bench(args.points, args.budget, args.seed)
    print_figures(result, args.json)
    return 0
