"""`shiproute plan --objective front`: plan the time-fuel front and write it (JSON, GeoJSON,
PNG, and each plan's RTZ)."""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path
from typing import Any

from ..front import TimeFuelFront, plan_front
from ..plan_request import PlanRequest
from ..plan_types import RoutePlan


def format_front(front: TimeFuelFront) -> str:
    """One line per plan (fastest first) and the front's notes."""
    shape = "monotone" if front.monotone else "NOT monotone"
    lines = [f"time-fuel front {' -> '.join(front.plans[0].ports)}: {len(front.plans)} plans "
             f"in {front.compute_time_s:.1f} s ({shape})",
             "  #   voyage h   fuel t   dist NM   mean kn  status"]
    for k, p in enumerate(front.plans):
        hours = p.total_time_s / 3600.0
        status = "ok" if p.feasible else "INFEASIBLE: " + "; ".join(p.infeasible_reasons)
        lines.append(f"  {k:<3d} {hours:9.1f} {p.total_fuel_t:8.1f} {p.total_distance_nm:9.1f} "
                     f"{p.total_distance_nm / max(hours, 1e-9):9.2f}  {status}")
    lines += [f"note       {n}" for n in front.notes]
    return "\n".join(lines)


def run_front(req: PlanRequest, sampler: Any, args: argparse.Namespace, forecast: Any,
              keywords: dict[str, Any]) -> int:
    """Plan, write and print the front; exit 0 when both ends are feasible, else 1."""
    from ..io.front_files import write_front_geojson, write_front_json, write_front_png
    from ..io.rtz import write_rtz

    def said(k: int, plan: RoutePlan) -> None:
        print(f"\rfront plan {k + 1}/{req.front_points}: {plan.total_time_s / 3600:.1f} h, "
              f"{plan.total_fuel_t:.1f} t", end="", file=sys.stderr, flush=True)

    front = plan_front(req, sampler, progress=said, **keywords)
    print(file=sys.stderr)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    stem = args.name or re.sub(r"[^A-Za-z0-9]+", "_",
                               "_".join(front.plans[0].ports)).strip("_") + "_front"
    write_front_json(front, out / f"{stem}.json")
    write_front_geojson(front, out / f"{stem}.geojson")
    for k, p in enumerate(front.plans):
        write_rtz(p, out / f"{stem}_{k}.rtz")
    if not args.no_plot:
        write_front_png(front, out / f"{stem}.png")
    print(format_front(front))
    print(f"files: {out / stem}.{{json,geojson{'' if args.no_plot else ',png'}}}, "
          f"{stem}_0..{len(front.plans) - 1}.rtz")
    del forecast
    ends_ok = front.plans[0].feasible and front.plans[-1].feasible
    return 0 if ends_ok else 1
