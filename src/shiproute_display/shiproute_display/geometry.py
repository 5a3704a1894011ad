"""Positions along a plan, the great circle, the engine-room stage at a time, ship's time zones.

Legs are drawn and interpolated as great-circle arcs on the sphere (mean Earth radius): at
12-hour legs the difference to the WGS 84 geodesic is far below a pixel of the page and the
display needs no geodesy library. Longitudes out are in -180..180 unless `unwrap` is asked.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from .model import Plan, Stage

RPM_CHANGE_MIN = 0.5  #: an RPM step smaller than this is not an order to the engine room [rev/min]


def _unit(lat_deg: float, lon_deg: float) -> np.ndarray:
    la, lo = math.radians(lat_deg), math.radians(lon_deg)
    return np.array([math.cos(la) * math.cos(lo), math.cos(la) * math.sin(lo), math.sin(la)])


def _lat_lon(v: np.ndarray) -> tuple[float, float]:
    x, y, z = (float(c) for c in v)
    return math.degrees(math.atan2(z, math.hypot(x, y))), math.degrees(math.atan2(y, x))


def slerp(lat1: float, lon1: float, lat2: float, lon2: float, f: float) -> tuple[float, float]:
    """Point a fraction `f` (0..1) of the way along the great circle from point 1 to point 2."""
    a, b = _unit(lat1, lon1), _unit(lat2, lon2)
    omega = math.acos(max(-1.0, min(1.0, float(a @ b))))
    if omega < 1e-12:
        return lat1, lon1
    s = math.sin(omega)
    return _lat_lon(math.sin((1 - f) * omega) / s * a + math.sin(f * omega) / s * b)


def great_circle(lat1: float, lon1: float, lat2: float, lon2: float,
                 n: int = 128) -> list[tuple[float, float]]:
    """`n` points (lat, lon) of the great circle from point 1 to point 2, both ends included."""
    return [slerp(lat1, lon1, lat2, lon2, k / (n - 1)) for k in range(n)]


def position_at(plan: Plan, t_s: float) -> tuple[float, float, int]:
    """Planned (lat, lon, leg index) at time `t_s`, clamped to departure and arrival."""
    w = plan.waypoints
    if t_s <= w[0].time_s:
        return w[0].lat_deg, w[0].lon_deg, 0
    for i in range(len(w) - 1):
        a, b = w[i], w[i + 1]
        if t_s <= b.time_s:
            span = b.time_s - a.time_s
            f = (t_s - a.time_s) / span if span > 0 else 1.0
            lat, lon = slerp(a.lat_deg, a.lon_deg, b.lat_deg, b.lon_deg, f)
            return lat, lon, i
    return w[-1].lat_deg, w[-1].lon_deg, len(w) - 2


def stage_index(stages: Sequence[Stage], t_s: float) -> int:
    """Index of the stage in force at `t_s`: -1 before the first, the last one after the end."""
    idx = -1
    for i, s in enumerate(stages):
        if t_s >= s.start_s:
            idx = i
    return idx


def next_rpm_change(stages: Sequence[Stage], t_s: float) -> tuple[float, float] | None:
    """(time, new RPM) of the next stage start after `t_s` whose RPM differs from the one in force
    by at least RPM_CHANGE_MIN; None when the RPM holds to the end of the schedule."""
    i = stage_index(stages, t_s)
    current = stages[i].shaft_rpm if i >= 0 else math.nan
    for s in stages[i + 1:]:
        if not math.isfinite(current) or abs(s.shaft_rpm - current) >= RPM_CHANGE_MIN:
            return s.start_s, s.shaft_rpm
    return None


def zone_offset_h(lon_deg: float) -> int:
    """Nautical time zone of a longitude: ship's time = UTC + this many hours (15 deg zones)."""
    if not math.isfinite(lon_deg):
        return 0
    lon = (lon_deg + 180.0) % 360.0 - 180.0
    return max(-12, min(12, round(lon / 15.0)))


def wrap_lon(lon_deg: float) -> float:
    """Longitude into -180..180."""
    return (lon_deg + 180.0) % 360.0 - 180.0


def unwrap(lons: Sequence[float], ref_deg: float) -> list[float]:
    """Longitudes made continuous, the first taken within 180 deg of `ref_deg`."""
    out: list[float] = []
    prev = ref_deg
    for lon in lons:
        v = prev + wrap_lon(lon - prev)
        out.append(v)
        prev = v
    return out


def split_antimeridian(points: Sequence[tuple[float, float]]) -> list[list[tuple[float, float]]]:
    """(lat, lon) polyline -> pieces with longitudes in -180..180 that never jump across 180:
    each crossing gets an interpolated point on +-180 ending one piece and starting the next."""
    pieces: list[list[tuple[float, float]]] = []
    if not points:
        return pieces
    lat0, lon0 = points[0]
    cur = [(lat0, wrap_lon(lon0))]
    cont_prev = lon0
    for lat, lon in points[1:]:
        cont = cont_prev + wrap_lon(lon - cont_prev)
        a, b = wrap_lon(cont_prev), wrap_lon(cont)
        if abs(b - a) > 180.0:  # crossed +-180 between the two points
            edge = 180.0 if a > 0 else -180.0
            da = edge - a
            f = da / (cont - cont_prev) if cont != cont_prev else 0.0
            lat_x = cur[-1][0] + f * (lat - cur[-1][0])
            cur.append((lat_x, edge))
            pieces.append(cur)
            cur = [(lat_x, -edge)]
        cur.append((lat, b))
        cont_prev = cont
    pieces.append(cur)
    return [p for p in pieces if len(p) >= 2]
