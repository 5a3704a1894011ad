"""World benchmark: plan every lane of `world_lanes.csv` (calm water, 5 s budget each) and
check each plan with the route check at GSHHG full resolution.

`world_lanes.csv` is a copy of the public lane set `benchmarks/world_lanes.csv` of the
shiproute project's shared data (20 trade lanes through Suez, Panama, Kiel, Dover,
Gibraltar, Malacca, the Bosphorus, Torres Strait, the Great Barrier Reef, the Elbe, the St
Lawrence). `holdout_lanes.csv` (`--lanes holdout`) is this project's own hold-out set: 33
voyages outside those lanes (ports up rivers, archipelagos, straits, canals the ship fits
and does not, ocean crossings, high latitudes, voyages with port calls in the optional `via`
column, separated by ';'), for checking on voyages the planner was not developed on.

A lane is land-clean when no sample of its track (every 0.25 NM) lies on GSHHG
full-resolution land outside 3 NM round each port (port calls included: the track is checked
berth to berth, as the plan checks itself) and outside canals (fixed passages under
their authorities' rules), and depth-checked when the plan was made
with bathymetry and every planned leg's depth was known or named by the plan as crossing a
coarse grid's coastal cells (`geo.coarse_coast`: no UKC constraint there, the coastline
decides; such legs are counted per lane, and `depth_fully_known_lanes` counts the lanes
without any).
"""

from __future__ import annotations

import argparse
import contextlib
import csv
import json
import statistics
import time
from datetime import timedelta
from importlib import resources

import numpy as np
from shiproute_core.bench_report import print_figures
from shiproute_core.units import M_PER_NM

from ... import planning
from ...errors import PlannerError
from ...io.files import write_plan_files
from ...plan_checks import berth_parts_checked
from ...request import PlanOptions, VoyageRequest, voyage_times
from ...route_check import check_track

LANE_SETS = {"world": "world_lanes.csv", "holdout": "holdout_lanes.csv"}


def _lanes(lanes: str) -> list[dict[str, str]]:
    """The lanes of a bundled set (`world`, `holdout`) or of a CSV file in their format
    (ValueError naming the file and what is wrong)."""
    if lanes in LANE_SETS:
        text = (resources.files("shiproute_planner.experiments.bench")
                / LANE_SETS[lanes]).read_text()
    else:
        try:
            with open(lanes, encoding="utf-8") as f:
                text = f.read()
        except OSError as exc:
            raise ValueError(f"--lanes {lanes!r}: cannot read the lane file "
                             f"({exc.strerror})") from None
    rows = list(csv.DictReader(text.splitlines()))
    missing = {"name", "from", "to", "depart", "rta_days", "ship"} - set(rows[0] if rows else ())
    if missing:
        raise ValueError(f"--lanes {lanes!r}: no lanes, or columns missing: "
                         f"{', '.join(sorted(missing))}")
    return rows


def _peak_rss_mb() -> float:
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024.0
    except (OSError, ValueError):
        pass
    return float("nan")


def _where(plan, leg: int) -> str:
    """Which part of a plan a leg belongs to (for finding the cause of a violation): an
    optimised span, a fixed passage (canal) or a computed coastal/strait passage, with the
    port or gate it follows."""
    last = ""
    for w in plan.waypoints[:leg + 1]:
        last = w.port or last
    kind = "coastal or strait passage"
    for a, b in plan.optimised_spans:
        if a <= leg < b:
            kind = "optimised span" + (" (first/last leg: seam)" if leg in (a, b - 1) else "")
    for a, b in plan.extra.get("fixed_passages", ()):
        if a <= leg < b:
            kind = "canal"
    return f"{kind} after {last}" if last else kind


def _voyage(lane: dict[str, str]) -> VoyageRequest:
    """The lane's voyage (calm water, the default bathymetry)."""
    depart_s, rta_s = voyage_times(lane["depart"], timedelta(days=float(lane["rta_days"])))
    via = tuple(p.strip() for p in (lane.get("via") or "").split(";") if p.strip())
    return VoyageRequest(lane["from"], lane["to"], depart_s, rta_s, lane["ship"], via=via,
                         default_bathymetry=True)


def _warm_process(lane: dict[str, str]) -> float:
    """Warm the process as the CLI and the planner node do before their clocks (compiled
    kernels, land and depth maps: the first lane set up with no search); its seconds. Without
    it the first lane's plan paid them (5-12 s of its 5-s budget: 0 generations)."""
    t0 = time.perf_counter()
    with contextlib.suppress(PlannerError):  # the lane's own plan says what is wrong
        planning.plan(_voyage(lane), PlanOptions(budget_s=0.0, max_generations=0,
                                                 with_baseline=False), None)
    return time.perf_counter() - t0


def _land_findings(plan, contains) -> list:
    """Land findings on the plan's track from berth to berth (port calls included), each
    part outside 3 NM round its berths and off the canals sailed as fixed passages."""
    result = berth_parts_checked(plan, lambda lon, lat, speed, a, b, skip: check_track(
        lon, lat, speed, contains, port_clearance_m=3.0 * M_PER_NM, skip_legs=skip))
    return [v for v in result.violations if v.kind == "land"]


def run(budget_s: float, only: list[str], lanes: list[dict[str, str]] | None = None,
        out_dir: str | None = None) -> dict:
    """Plan and check every lane (`lanes`: rows of `_lanes`, the public set by default); the
    JSON-able result (plan files into `out_dir` if given)."""
    from ...cli.check import land_test

    land_full, land_note = land_test(None)
    rows, times = [], []
    chosen = [lane for lane in (_lanes("world") if lanes is None else lanes)
              if not only or lane["name"] in only]
    warm_s = _warm_process(chosen[0]) if chosen else 0.0
    for lane in chosen:
        row: dict = {"lane": lane["name"], "passes": lane["passes"]}
        t = time.perf_counter()
        try:
            plan = planning.plan(_voyage(lane), PlanOptions(budget_s=budget_s), None)
        except PlannerError as exc:
            row.update(error=str(exc), plan_s=round(time.perf_counter() - t, 2))
            rows.append(row)
            continue
        dt = time.perf_counter() - t
        times.append(dt)
        if out_dir:
            write_plan_files(plan, out_dir, stem=lane["name"], png=False)
        land = _land_findings(plan, land_full.contains)
        depths = np.array([w.min_depth_m for w in plan.waypoints[:-1]])
        planned = np.zeros(depths.size, dtype=bool)
        for a, b in plan.optimised_spans:
            planned[a:b] = True
        with_depth = not any(w.startswith("depth not checked:") for w in plan.warnings)
        near_coast = np.zeros(depths.size, dtype=bool)
        near_coast[[k for k in plan.extra.get("depth_coarse_near_coast", {}).get("legs", ())
                    if k < depths.size]] = True
        unknown = planned & ~np.isfinite(depths)
        row.update(
            plan_s=round(dt, 2), feasible=plan.feasible,
            infeasible_reasons=list(plan.infeasible_reasons),
            land_legs_full_res=[(v.leg, round(v.lat_deg, 3), round(v.lon_deg, 3),
                                 round(v.value, 2)) for v in land],
            land_where=sorted({f"leg {v.leg}: {_where(plan, v.leg)}" for v in land}),
            flagged_legs=[f"leg {k} ({w.lat_deg:.3f}, {w.lon_deg:.3f}) flags "
                          f"{w.constraint_flags} ukc {w.ukc_m:.1f} m: {_where(plan, k)}"
                          for k, w in enumerate(plan.waypoints[:-1]) if w.constraint_flags][:12],
            # checked: every planned leg's depth known, or named by the plan as crossing
            # coarse coastal cells (no UKC constraint there: the coastline decides)
            depth_checked=with_depth and not bool(np.any(unknown & ~near_coast)),
            depth_fully_known=with_depth and not bool(np.any(unknown)),
            depth_unknown_legs=int(np.count_nonzero(~np.isfinite(depths))),
            depth_near_coast_legs=int(np.count_nonzero(near_coast)),
            min_ukc_m=round(float(np.nanmin([w.ukc_m for w in plan.waypoints[:-1]])), 1)
            if np.isfinite(depths).any() else None,
            land_repairs=[r["text"] for r in plan.extra.get("land_repairs", ())],
            distance_nm=round(plan.total_distance_nm, 1), fuel_t=round(plan.total_fuel_t, 1),
            warnings=list(plan.warnings))
        rows.append(row)
    ok = [r for r in rows if "error" not in r]
    return {
        "lanes": len(rows),
        "feasible_lanes": sum(r["feasible"] for r in ok),
        "land_clean_lanes": sum(not r["land_legs_full_res"] for r in ok),
        "depth_checked_lanes": sum(r["depth_checked"] for r in ok),
        "land_repaired_lanes": sum(bool(r["land_repairs"]) for r in ok),
        "depth_fully_known_lanes": sum(r["depth_fully_known"] for r in ok),
        "failed_lanes": [r["lane"] for r in rows if "error" in r],
        "median_plan_s": round(statistics.median(times), 2) if times else None,
        "max_plan_s": round(max(times), 2) if times else None,
        "process_warm_up_s": round(warm_s, 2),
        "planner_rss_mb": round(_peak_rss_mb(), 1),
        "land_check": land_note,
        "per_lane": rows,
    }


def main(argv: list[str]) -> int:
    """`shiproute bench world [--json] [--budget S] [--lane NAME ...] [--lanes SET|FILE]
    [--out DIR]`."""
    ap = argparse.ArgumentParser(prog="shiproute bench world", description=__doc__)
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    ap.add_argument("--budget", type=float, default=5.0, help="planning budget per lane [s]")
    ap.add_argument("--lane", action="append", default=[], help="only these lanes")
    ap.add_argument("--lanes", default="world",
                    help="lane set: world (the public 20), holdout (our own hold-out set) or "
                         "a CSV file in their format (default world)")
    ap.add_argument("--out", default=None,
                    help="write each lane's plan files (RTZ, GeoJSON, JSON) into this directory")
    args = ap.parse_args(argv)
    try:
        lanes = _lanes(args.lanes)
    except ValueError as exc:  # a bad lane file is the user's mistake: exit 2, no traceback
        ap.error(str(exc))
    result = run(args.budget, args.lane, lanes, args.out)
    print_figures(result, args.json, leave_out=("per_lane",))
    if not args.json:
        for r in result["per_lane"]:
            print(json.dumps(r))
    return 0
