"""Plain-JSON payloads of the page: a plan with its engine-room schedule, a fix, a history row.

Numbers stay SI/POSIX where the page computes (times), in bridge units where it only shows
(kn, NM, t, deg true); NaN becomes null.
"""

from __future__ import annotations

import math
from typing import Any

from .geometry import position_at, zone_offset_h
from .model import EnsembleSpread, Plan, Profile, ShipFix, Stage


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
    legs = {round(w.time_s): (k, w) for k, w in enumerate(plan.waypoints[:-1])}
    spread = plan.ensemble
    rows = []
    for i, s in enumerate(stages_of(plan, profile)):
        k, leg = legs.get(round(s.start_s), (-1, None))
        lat, lon, _ = position_at(plan, s.start_s)
        rows.append({
            "stage": i + 1, "start_s": s.start_s, "duration_s": num(s.duration_s, 0),
            "zone_h": zone_offset_h(lon), "lat_deg": num(lat, 3), "lon_deg": num(lon, 3),
            "rpm": num(s.shaft_rpm, 3), "heading_deg": num(s.heading_deg, 3),
            "sog_kn": num(leg.sog_kn, 3) if leg else None,
            "fuel_t": num(leg.leg_fuel_t, 3) if leg else None,
            "hs_m": num(leg.hs_m, 3) if leg else None,
            "flags": int(leg.constraint_flags) if leg else 0,
            "hs_min_m": _leg_value(spread.leg_hs_min_m, k) if spread else None,
            "hs_max_m": _leg_value(spread.leg_hs_max_m, k) if spread else None,
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
        "ensemble": ensemble_payload(plan.ensemble) if plan.ensemble else None,
    }


def _leg_value(values: tuple[float, ...], k: int) -> float | None:
    return num(values[k], 2) if 0 <= k < len(values) else None


def ensemble_payload(e: EnsembleSpread) -> dict[str, Any]:
    """A plan's spread over forecast members: P10/P50/P90 of fuel and ETA, risks, leg Hs."""
    return {
        "members": e.members, "risk_measure": e.risk_measure or "mean forecast",
        "fuel_quantiles_t": [num(v, 1) for v in e.fuel_quantiles_t],
        "eta_quantiles_s": [num(v, 0) for v in e.eta_quantiles_s],
        "p_hs_violation": num(e.p_hs_violation, 3), "p_late": num(e.p_late, 3),
        "leg_hs_min_m": [num(v, 2) for v in e.leg_hs_min_m],
        "leg_hs_median_m": [num(v, 2) for v in e.leg_hs_median_m],
        "leg_hs_max_m": [num(v, 2) for v in e.leg_hs_max_m],
        "leg_wind_min_m_s": [num(v, 1) for v in e.leg_wind_min_m_s],
        "leg_wind_max_m_s": [num(v, 1) for v in e.leg_wind_max_m_s],
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
