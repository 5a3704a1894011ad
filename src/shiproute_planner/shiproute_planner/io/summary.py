"""Machine-readable plan summary (JSON) and GeoJSON of the route with per-leg properties."""

from __future__ import annotations

import json
import math
from dataclasses import asdict
from datetime import UTC, datetime
from pathlib import Path

from ..errors import OutputError
from ..plan_types import RoutePlan


def _iso(t_s: float) -> str:
    return datetime.fromtimestamp(t_s, UTC).strftime("%Y-%m-%dT%H:%M:%SZ")


def _clean(v):
    """NaN/inf -> None so the JSON is standard."""
    if isinstance(v, float) and not math.isfinite(v):
        return None
    if isinstance(v, dict):
        return {k: _clean(x) for k, x in v.items()}
    if isinstance(v, list | tuple):
        return [_clean(x) for x in v]
    return v


def plan_summary(plan: RoutePlan) -> dict:
    """Totals, baseline comparison, constraint status and per-leg values."""
    legs = []
    for k, w in enumerate(plan.waypoints[:-1]):
        legs.append({"leg": k, "start_time": _iso(w.time_s), **{
            key: getattr(w, key) for key in (
                "lat_deg", "lon_deg", "heading_deg", "shaft_rpm", "stw_kn", "sog_kn",
                "leg_distance_nm", "leg_duration_s", "leg_fuel_t", "brake_power_kw", "hs_m",
                "wave_from_deg", "wind_speed_m_s", "wind_from_deg", "p_slamming",
                "p_deck_wetness", "p_propeller_emergence", "constraint_flags", "port",
                "min_depth_m", "ukc_m")}})
    return _clean({
        "plan_id": plan.plan_id, "method": plan.method, "seed_source": plan.seed_source,
        "objective": plan.objective, "ship": plan.ship_name, "cycle_id": plan.cycle_id,
        "ports": list(plan.ports), "departure": _iso(plan.departure_s),
        "rta": _iso(plan.rta_s), "eta": _iso(plan.eta_s),
        "eta_minus_rta_h": (plan.eta_s - plan.rta_s) / 3600.0,
        "feasible": plan.feasible, "infeasible_reasons": list(plan.infeasible_reasons),
        "warnings": list(plan.warnings),
        "forecast": plan.extra.get("forecast"),
        "ensemble": plan.extra.get("ensemble"),
        "land_repairs": plan.extra.get("land_repairs", []),
        "lane_narrows": plan.extra.get("lane_narrows", []),
        "total_fuel_t": plan.total_fuel_t, "total_distance_nm": plan.total_distance_nm,
        "total_time_h": plan.total_time_s / 3600.0,
        "baseline": {"method": plan.baseline_method, "fuel_t": plan.baseline_fuel_t,
                     "distance_nm": plan.baseline_distance_nm, "rpm": plan.baseline_rpm,
                     "eta": _iso(plan.baseline_eta_s) if math.isfinite(plan.baseline_eta_s)
                     else None, "feasible": plan.baseline_feasible},
        "fuel_saving_t": plan.fuel_saving_t, "fuel_saving_pct": plan.fuel_saving_pct,
        "compute_time_s": plan.compute_time_s,
        # where the compute time went: set-up, passages, baselines, search, checks [s]
        "timing_s": plan.extra.get("timing_s"), "generations": plan.generations,
        "evaluations": plan.evaluations, "stage_h": plan.stage_s / 3600.0,
        "legs": legs,
    })


def write_json(plan: RoutePlan, path: str | Path) -> Path:
    """Write the plan summary as JSON."""
    return _write(Path(path), plan_summary(plan))


def plan_geojson(plan: RoutePlan) -> dict:
    """FeatureCollection: one LineString per leg (properties = leg values) + port points."""
    feats = []
    for k, (a, b) in enumerate(zip(plan.waypoints[:-1], plan.waypoints[1:], strict=True)):
        lon_b = a.lon_deg + ((b.lon_deg - a.lon_deg + 180.0) % 360.0 - 180.0)
        props = {key: v for key, v in asdict(a).items() if key not in ("lat_deg", "lon_deg")}
        props.update(leg=k, start_time=_iso(a.time_s), end_time=_iso(b.time_s))
        feats.append({"type": "Feature", "properties": props, "geometry": {
            "type": "LineString", "coordinates": [[a.lon_deg, a.lat_deg], [lon_b, b.lat_deg]]}})
    for w in plan.waypoints:
        if w.port:
            feats.append({"type": "Feature", "properties": {"port": w.port,
                                                            "time": _iso(w.time_s)},
                          "geometry": {"type": "Point", "coordinates": [w.lon_deg, w.lat_deg]}})
    return _clean({"type": "FeatureCollection", "properties": {
        "plan_id": plan.plan_id, "method": plan.method, "total_fuel_t": plan.total_fuel_t,
        "feasible": plan.feasible}, "features": feats})


def write_geojson(plan: RoutePlan, path: str | Path) -> Path:
    """Write the route as GeoJSON."""
    return _write(Path(path), plan_geojson(plan))


def _write(path: Path, data: dict) -> Path:
    try:
        path.write_text(json.dumps(data, indent=1))
    except OSError as exc:
        raise OutputError(f"cannot write {path}: {exc}") from exc
    return path
