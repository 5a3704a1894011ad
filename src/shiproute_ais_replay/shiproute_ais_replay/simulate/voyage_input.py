"""Voyage inputs for ``bag simulate``: RTZ route + schedule, planner plan JSON, or great circle.

A ``VoyagePlan`` lists waypoints and, per leg, what to hold: shaft RPM, or a speed through
water, or an ETA at the leg's end (NaN where not given; the CLI default RPM fills gaps).
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
from shiproute_planner.errors import RouteFileError
from shiproute_planner.io.rtz_read import read_rtz as read_route_rtz

from ..ais.ais_nmea import parse_time_ns
from ..errors import SimulationError


@dataclass(frozen=True)
class VoyagePlan:
    """Waypoints [deg] and per-leg targets (arrays of length n_waypoints - 1)."""

    lat_deg: np.ndarray
    lon_deg: np.ndarray
    leg_rpm: np.ndarray
    leg_stw_kn: np.ndarray
    leg_eta_s: np.ndarray  # POSIX s at the END of each leg
    departure_s: float  # NaN when the input has none
    ship: str = ""
    source: str = ""

    def __post_init__(self) -> None:
        n = len(self.lat_deg)
        if n < 2 or len(self.lon_deg) != n:
            raise SimulationError(f"voyage from {self.source or 'input'} needs >= 2 waypoints")
        for name in ("leg_rpm", "leg_stw_kn", "leg_eta_s"):
            if len(getattr(self, name)) != n - 1:
                raise SimulationError(f"{name} of {self.source} must have {n - 1} legs")


def _num(text: str | None) -> float:
    try:
        return float(text) if text not in (None, "") else math.nan
    except ValueError:
        return math.nan


def _time_s(text: str | None) -> float:
    t_ns = parse_time_ns(text) if text else None
    return t_ns / 1e9 if t_ns is not None else math.nan


def read_rtz(path: str | Path) -> VoyagePlan:
    """Read an RTZ (1.0-1.2) route through the planner's RTZ reader: waypoints and the first
    (calculated, else manual) schedule.

    scheduleElement attributes used: ``rpm``, ``speed`` (kn, taken as speed through water),
    ``eta`` (at that waypoint) and ``etd`` (of the first waypoint = departure)."""
    try:
        rtz = read_route_rtz(path)
    except RouteFileError as exc:
        raise SimulationError(str(exc)) from None
    n = len(rtz.waypoint_ids)
    rpm, stw, eta = (np.full(max(n - 1, 0), math.nan) for _ in range(3))
    departure = math.nan
    for i, wid in enumerate(rtz.waypoint_ids):
        el = rtz.schedule.get(wid)
        if el is None:
            continue
        if i == 0:
            departure = _time_s(el.get("etd"))
        if i < n - 1:  # values at a waypoint apply to the leg starting there
            rpm[i], stw[i] = _num(el.get("rpm")), _num(el.get("speed"))
        if i > 0:
            eta[i - 1] = _time_s(el.get("eta"))
    return VoyagePlan(rtz.lat_deg, rtz.lon_deg, rpm, stw, eta, departure, source=str(path))


def read_plan_json(path: str | Path) -> VoyagePlan:
    """Read a plan JSON: the planner's summary (``legs``; its sibling .rtz gives the route and
    schedule), or ``waypoints`` with ``lat_deg``/``lon_deg`` (or
    ``latitude_deg``/``longitude_deg``), ``time_s`` (or ISO ``time``), ``shaft_rpm``;
    top level ``departure_s`` and ``ship_name`` when present."""
    path = Path(path)
    try:
        doc = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        raise SimulationError(f"cannot read plan JSON {path}: {exc}") from exc
    if "waypoints" not in doc and "legs" in doc:
        # planner summary (io.summary): legs hold start points only; the arrival point is in
        # the RTZ written next to it by write_plan_files
        sibling = path.with_suffix(".rtz")
        if not sibling.is_file():
            raise SimulationError(f"plan summary {path} has no arrival point; pass {sibling}")
        plan = read_rtz(sibling)
        return replace(plan, ship=str(doc.get("ship", "")))
    try:
        wps = doc["waypoints"]
        lat = np.array([float(w.get("lat_deg", w.get("latitude_deg"))) for w in wps])
        lon = np.array([float(w.get("lon_deg", w.get("longitude_deg"))) for w in wps])
    except (ValueError, KeyError, TypeError) as exc:
        raise SimulationError(f"cannot read plan JSON {path}: {exc}") from exc
    times = np.array([float(w["time_s"]) if "time_s" in w else _time_s(w.get("time"))
                      for w in wps])
    rpm = np.array([_num(str(w.get("shaft_rpm", ""))) for w in wps[:-1]])
    stw = np.array([_num(str(w.get("stw_kn", ""))) for w in wps[:-1]])
    dep = float(doc.get("departure_s", times[0] if len(times) else math.nan))
    return VoyagePlan(lat, lon, rpm, stw, times[1:], dep, str(doc.get("ship_name", "")),
                      str(path))


def great_circle(from_lat: float, from_lon: float, to_lat: float, to_lon: float,
                 rpm: float) -> VoyagePlan:
    """Two-waypoint voyage held at one RPM (steering recomputes the great-circle bearing)."""
    one = np.array([rpm])
    return VoyagePlan(np.array([from_lat, to_lat]), np.array([from_lon, to_lon]), one,
                      np.array([math.nan]), np.array([math.nan]), math.nan,
                      source="great circle")


def read_voyage(path: str | Path) -> VoyagePlan:
    """RTZ or plan JSON by file suffix."""
    path = Path(path)
    if path.suffix.lower() == ".json":
        return read_plan_json(path)
    return read_rtz(path)
