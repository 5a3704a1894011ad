"""Voyages benchmark: the reference study's application 1 (Shanghai -> Ningbo -> Xiamen ->
Yantian -> Singapore -> Felixstowe -> Rotterdam -> Gdansk, 28-day RTA, calm water) planned as
one multi-port voyage, and a 6-hour short-sea passage (Rostock -> Trelleborg, 80 NM across
the western Baltic, the ferries' 6-hour crossing), each against the constant-RPM baseline
over the same time.

`figures()` builds the whole result dict (other voyage figures are merged into it there).
"""

from __future__ import annotations

import argparse
import time

from shiproute_core.bench_report import print_figures

MULTIPORT = ("Shanghai", ("Ningbo", "Xiamen", "Yantian", "Singapore", "Felixstowe",
                          "Rotterdam"), "Gdansk", "2026-06-01T00:00Z", "28d")
SHORTSEA = ("Rostock", "Trelleborg", "2026-06-01T08:00Z", "6h")


def plan_multiport(budget: str = "8s", seed: int = 0, via: tuple[str, ...] | None = None):
    """The application-1 plan (calm water); `via` replaces the port calls (windows)."""
    from ...plan_request import build_request, run_request

    a, vias, b, depart, rta = MULTIPORT
    req = build_request(origin=a, destination=b, depart=depart, rta=rta,
                        via=list(via if via is not None else vias), budget=budget, seed=seed)
    return run_request(req, None)


def plan_shortsea(budget: str = "3s", seed: int = 0, stage_hours: float | None = None):
    """The 6-hour short-sea passage (calm water), stage length derived unless given."""
    from ...plan_request import build_request, run_request

    a, b, depart, rta = SHORTSEA
    req = build_request(origin=a, destination=b, depart=depart, rta=rta, budget=budget,
                        seed=seed, stage_hours=stage_hours)
    return run_request(req, None)


def optimised_stages(plan) -> int:
    """Stages of the plan's optimised spans (the approaches are fixed pilotage)."""
    return int(sum(end - start for start, end in plan.optimised_spans))


def figures(seed: int = 0) -> dict:
    """The benchmark's figures as one dict (JSON-ready)."""
    from .front import front_bench

    plan_shortsea("0.5s", seed)  # warm: ports, land mask, kernels, sea-lane graph
    t0 = time.perf_counter()
    multi = plan_multiport(seed=seed)
    multi_s = time.perf_counter() - t0
    short = plan_shortsea(seed=seed)
    front = front_bench(points=9, seed=seed)  # 9-point time-fuel front, Busan -> Long Beach
    return {
        "multiport_plan_s": round(multi_s, 2),
        "multiport_fuel_t": round(multi.total_fuel_t, 1),
        "multiport_baseline_t": round(multi.baseline_fuel_t, 1),
        "multiport_feasible": bool(multi.feasible),
        "multiport_legs": len(multi.ports) - 1,
        "shortsea_stages": optimised_stages(short),
        "shortsea_fuel_t": round(short.total_fuel_t, 3),
        "shortsea_baseline_t": round(short.baseline_fuel_t, 3),
        "shortsea_feasible": bool(short.feasible),
        "shortsea_stage_h": round(short.stage_s / 3600.0, 3),
        "front_points": front["front_points"],
        "front_s": front["front_s"],
        "front_monotone": front.get("front_monotone"),
        "front_ends_feasible": front.get("front_ends_feasible"),
    }


def main(argv: list[str]) -> int:
    """`shiproute bench voyages [--json] [--seed N]`."""
    ap = argparse.ArgumentParser(prog="shiproute bench voyages", description=__doc__)
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args(argv)
    result = figures(args.seed)
    print_figures(result, args.json)
    return 0
