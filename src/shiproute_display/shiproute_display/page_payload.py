"""Plain-JSON payloads of the page: a plan with its engine-room schedule, a fix, a history row.

Numbers stay SI/POSIX where the page computes (times), in bridge units where it only shows
(kn, NM, t, deg true); NaN becomes null.
"""

from __future__ import annotations

import math
from typing import Any

from .geometry import position_at, zone_offset_h
from .model import Plan, Profile, ShipFix, Stage


def num(v: float, digits: int = 3) -> float | None:
    """Rounded finite value or None (JSON null)."""
    return round(float(v), digits) if v is not None and math.isfinite(v) else None


def trigger_kind(trigger: str) -> str:
    """The planner's re-plan reason in one word: cycle, off-plan, request, start, voyage."""
    t = trigger.lower()
    if "cycle" in t:
        return "new cycle"
    if "off plan" in t or "off-plan" in t:
        return "off plan"
    if "first ship" in t:
        return "start"
    if "voyage" in t:
        return "voyage set"
    if t:
        return "request"
    return "unknown"


def stages_of(plan: Plan, profile: Profile | None) -> list[Stage]:
    """The engine-room stages: from the plan's RpmProfile when it has arrived, else its legs."""
    if profile is not None and profile.plan_id == plan.plan_id and profile.stages:
        return list(profile.stages)
    return [Stage(w.time_s, w.leg_duration_s, w.shaft_rpm, w.heading_deg)
            for w in plan.waypoints[:-1]]


def schedule_rows(plan: Plan, profile: Profile | None) -> list[dict[str, Any]]:
    """One row per stage: start (UTC s + ship's zone), RPM, heading, expected SOG, fuel, Hs."""
    legs = {round(w.time_s): w for w in plan.waypoints[:-1]}
    rows = []
    for i, s in enumerate(stages_of(plan, profile)):
        leg = legs.get(round(s.start_s))
        lat, lon, _ = position_at(plan, s.start_s)
        rows.append({
            "stage": i + 1, "start_s": s.start_s, "duration_s": num(s.duration_s, 0),
            "zone_h": zone_offset_h(lon), "lat_deg": num(lat, 3), "lon_deg": num(lon, 3),
            "rpm": num(s.shaft_rpm, 3), "heading_deg": num(s.heading_deg, 3),
            "sog_kn": num(leg.sog_kn, 3) if leg else None,
            "fuel_t": num(leg.leg_fuel_t, 3) if leg else None,
            "hs_m": num(leg.hs_m, 3) if leg else None,
            "flags": int(leg.constraint_flags) if leg else 0,
        })
    return rows


def plan_payload(plan: Plan, profile: Profile | None) -> dict[str, Any]:
    """Header, nodes and schedule of a plan for the page."""
    w = plan.waypoints
    saved = plan.fuel_saving_t
    return {
        "plan_id": plan.plan_id, "cycle_id": plan.cycle_id, "method": plan.method,
        "objective": plan.objective, "ship_name": plan.ship_name, "trigger": plan.trigger,
        "trigger_kind": trigger_kind(plan.trigger), "stamp_s": num(plan.stamp_s),
        "departure_s": num(plan.departure_s), "rta_s": num(plan.rta_s), "eta_s": num(plan.eta_s),
        "eta_minus_rta_h": num((plan.eta_s - plan.rta_s) / 3600.0, 4),
        "feasible": plan.feasible, "infeasible_reasons": list(plan.infeasible_reasons),
        "warnings": list(plan.warnings), "total_fuel_t": num(plan.total_fuel_t, 4),
        "total_distance_nm": num(plan.total_distance_nm, 3),
        "baseline_fuel_t": num(plan.baseline_fuel_t, 4), "fuel_saved_t": num(saved, 4),
        "fuel_saved_pct": num(100.0 * saved / plan.baseline_fuel_t, 4)
        if math.isfinite(saved) else None,
        "compute_time_s": num(plan.compute_time_s, 4),
        "waypoint_count": len(w),
        "lat": [round(p.lat_deg, 4) for p in w], "lon": [round(p.lon_deg, 4) for p in w],
        "time_s": [p.time_s for p in w],
        "leg_rpm": [num(p.shaft_rpm, 3) for p in w[:-1]],
        "leg_fuel_t_per_day": [num(p.leg_fuel_t / p.leg_duration_s * 86400.0, 1)
                               if p.leg_duration_s > 0 else None for p in w[:-1]],
        "leg_hs_m": [num(p.hs_m, 3) for p in w[:-1]],
        "schedule": schedule_rows(plan, profile),
    }


def history_row(plan: Plan, before: Plan | None) -> dict[str, Any]:
    """A re-plan: when, why, on which cycle, and what it changed in ETA and fuel."""
    return {
        "plan_id": plan.plan_id, "stamp_s": num(plan.stamp_s), "cycle_id": plan.cycle_id,
        "trigger": plan.trigger, "trigger_kind": trigger_kind(plan.trigger),
        "eta_s": num(plan.eta_s), "total_fuel_t": num(plan.total_fuel_t, 4),
        "feasible": plan.feasible, "warnings": len(plan.warnings),
        "d_eta_h": num((plan.eta_s - before.eta_s) / 3600.0, 4) if before else None,
        "d_fuel_t": num(plan.total_fuel_t - before.total_fuel_t, 4) if before else None,
    }


def fix_payload(fix: ShipFix) -> dict[str, Any]:
    """A fix for the page."""
    return {"time_s": fix.time_s, "lat_deg": round(fix.lat_deg, 5),
            "lon_deg": round(fix.lon_deg, 5), "sog_kn": num(fix.sog_kn, 2),
            "cog_deg": num(fix.cog_deg, 1), "heading_deg": num(fix.heading_deg, 1),
            "shaft_rpm": num(fix.shaft_rpm, 1), "fuel_rate_t_per_h": num(fix.fuel_rate_t_per_h),
            "mmsi": fix.mmsi}
