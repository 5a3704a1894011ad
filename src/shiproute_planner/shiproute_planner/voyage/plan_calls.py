"""A multi-port plan's port calls: per-leg arrival and departure as planned next to the
schedule and the window, and the schedule's reasons when it cannot meet a window."""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from typing import Any

from ..plan_types import RoutePlan
from .schedule import LegSpec, Schedule, iso


def call_rows(legs: Sequence[LegSpec], sched: Schedule, arrivals: Sequence[float],
              tolerance_s: float) -> list[dict[str, Any]]:
    """One row per end port: planned arrival/departure, scheduled ones, window, verdict."""
    rows = []
    for k, leg in enumerate(legs):
        arr = float(arrivals[k]) if k < len(arrivals) else float("nan")
        start = max(arr, leg.earliest_s) if leg.earliest_s is not None else arr
        last = k == len(legs) - 1
        dep = start if last else start + leg.berth_s
        late = leg.latest_s is not None and arr > leg.latest_s + tolerance_s
        rows.append({
            "port": leg.name, "arrival": iso(arr), "departure": iso(dep),
            "arrival_s": arr, "departure_s": dep,
            "scheduled_arrival": iso(sched.arrival_s[k]),
            "scheduled_departure": iso(sched.departure_s[k]),
            "wait_h": round((start - arr) / 3600.0, 2),
            "berth_h": 0.0 if last else round(leg.berth_s / 3600.0, 2),
            "earliest": iso(leg.earliest_s) if leg.earliest_s is not None else "",
            "latest": iso(leg.latest_s) if leg.latest_s is not None else "",
            "in_window": not late,
            "canal": leg.fixed_s is not None,
        })
    return rows


def with_port_calls(plan: RoutePlan, legs: Sequence[LegSpec], sched: Schedule,
                    arrivals: Sequence[float], ports: Sequence[Any],
                    tolerance_s: float) -> RoutePlan:
    """`plan` with `extra['port_calls']` and, when the schedule cannot meet a window, flagged
    infeasible with the schedule's reasons (a best-effort plan)."""
    rows = call_rows(legs, sched, arrivals, tolerance_s)
    reasons = list(plan.infeasible_reasons)
    notes = []
    for r in rows:
        if not r["in_window"] and not sched.reasons:
            reasons.append(f"{r['port']}: arrives {r['arrival']}, after its latest arrival "
                           f"{r['latest']}")
    if sched.reasons:
        reasons += [f"schedule: {why}" for why in sched.reasons]
        notes.append("port-call windows cannot all be met; best-effort schedule: "
                     + "; ".join(sched.reasons))
    extra = {**plan.extra, "port_calls": rows,
             "schedule": {"feasible": sched.feasible, "reasons": list(sched.reasons),
                          "fuel_estimate_t": round(sched.fuel_estimate_t, 1),
                          "origin": ports[0].name}}
    return dataclasses.replace(plan, extra=extra, feasible=plan.feasible and not (
        len(reasons) > len(plan.infeasible_reasons)), infeasible_reasons=tuple(
        dict.fromkeys(reasons)), warnings=(*plan.warnings, *notes))
