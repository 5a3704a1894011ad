"""The chart as GeoJSON (RFC 7946) for Foxglove's Map panel: plan, previous plan, great circle,
track and ship, lines split at the antimeridian so no line is drawn round the world.

Feature properties carry `name` and a `style` (`color`, `weight`, `opacity`, `dashArray`:
Leaflet path options, meant for Foxglove's Leaflet-based Map panel; not checked against
Foxglove itself here). Viewers that do not read them ignore them.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from datetime import UTC, datetime
from typing import Any

from .geometry import great_circle, split_antimeridian
from .model import Plan, ShipFix

PLAN_COLOR = "#1f9e89"
PREVIOUS_COLOR = "#8a8f98"
GREAT_CIRCLE_COLOR = "#c9a227"
TRACK_COLOR = "#3b82f6"
SHIP_COLOR = "#e4572e"


def _iso(t_s: float) -> str:
    return datetime.fromtimestamp(t_s, UTC).strftime("%Y-%m-%dT%H:%M:%SZ")


def _clean(v: float) -> float | None:
    return round(v, 4) if math.isfinite(v) else None


def line_feature(points: Sequence[tuple[float, float]], name: str,
                 style: dict[str, Any], **props: Any) -> dict[str, Any] | None:
    """(lat, lon) polyline -> MultiLineString feature (split at 180); None when < 2 points."""
    pieces = split_antimeridian(points)
    if not pieces:
        return None
    coords = [[[round(lon, 5), round(lat, 5)] for lat, lon in piece] for piece in pieces]
    return {"type": "Feature", "properties": {"name": name, "style": style, **props},
            "geometry": {"type": "MultiLineString", "coordinates": coords}}


def point_feature(lat: float, lon: float, name: str, style: dict[str, Any],
                  **props: Any) -> dict[str, Any]:
    """Point feature (longitude wrapped into -180..180)."""
    lon = (lon + 180.0) % 360.0 - 180.0
    return {"type": "Feature", "properties": {"name": name, "style": style, **props},
            "geometry": {"type": "Point", "coordinates": [round(lon, 5), round(lat, 5)]}}


def plan_points(plan: Plan) -> list[tuple[float, float]]:
    """(lat, lon) of the plan's nodes."""
    return [(w.lat_deg, w.lon_deg) for w in plan.waypoints]


def baseline_points(plan: Plan, n: int = 96) -> list[tuple[float, float]]:
    """The great circle from the plan's first to its last node."""
    a, b = plan.waypoints[0], plan.waypoints[-1]
    return great_circle(a.lat_deg, a.lon_deg, b.lat_deg, b.lon_deg, n)


def chart_geojson(plan: Plan | None, previous: Plan | None, voyage_start: Plan | None,
                  track: Sequence[tuple[float, float]], ship: ShipFix | None) -> dict[str, Any]:
    """FeatureCollection of everything the chart shows (empty collection when nothing yet)."""
    feats: list[dict[str, Any] | None] = []
    if voyage_start is not None:
        feats.append(line_feature(baseline_points(voyage_start), "great circle (reference)",
                                  {"color": GREAT_CIRCLE_COLOR, "weight": 2, "opacity": 0.8,
                                   "dashArray": "6 6"}))
    if previous is not None:
        feats.append(line_feature(plan_points(previous), f"previous plan {previous.plan_id}",
                                  {"color": PREVIOUS_COLOR, "weight": 2, "opacity": 0.5},
                                  plan_id=previous.plan_id))
    if plan is not None:
        feats.append(line_feature(
            plan_points(plan), f"plan {plan.plan_id}",
            {"color": PLAN_COLOR, "weight": 4, "opacity": 1.0}, plan_id=plan.plan_id,
            cycle_id=plan.cycle_id, total_fuel_t=_clean(plan.total_fuel_t),
            eta=_iso(plan.eta_s), rta=_iso(plan.rta_s), feasible=plan.feasible,
            warnings=list(plan.warnings)))
        for i, w in enumerate(plan.waypoints[:-1]):
            feats.append(point_feature(
                w.lat_deg, w.lon_deg, f"stage {i + 1}: {w.shaft_rpm:.1f} rpm",
                {"color": PLAN_COLOR, "opacity": 1.0}, time=_iso(w.time_s),
                shaft_rpm=_clean(w.shaft_rpm), heading_deg=_clean(w.heading_deg),
                sog_kn=_clean(w.sog_kn)))
    if len(track) >= 2:
        feats.append(line_feature(track, "ship track", {"color": TRACK_COLOR, "weight": 2,
                                                        "opacity": 0.9}))
    if ship is not None:
        feats.append(point_feature(ship.lat_deg, ship.lon_deg, "own ship",
                                   {"color": SHIP_COLOR, "opacity": 1.0},
                                   time=_iso(ship.time_s), sog_kn=_clean(ship.sog_kn),
                                   cog_deg=_clean(ship.cog_deg)))
    return {"type": "FeatureCollection", "features": [f for f in feats if f is not None]}
