"""Port approaches: the first and last `approach_m` of a voyage follow the sea lane.

Harbours and estuaries (Busan's inner harbour, the Tagus, Long Beach behind its breakwaters)
cannot be entered by a straight 12-hour leg. The planner therefore optimises between the sea
ends of the approaches and sails the approaches themselves along the `searoute` lane at a
fixed RPM (pilotage waters: not land-checked, the lane's own geometry is trusted).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .ga.seeds import _searoute_coords
from .geo.geodesy import direct, inverse, unwrap_near, wrap_lon
from .geo.ports import Port
from .route.environment import Environment
from .route.evaluation import RouteEvaluation
from .route.problem import RouteLimits, RouteProblem
from .route.sail import sail_tracks


@dataclass(frozen=True)
class Approach:
    """A polyline in sailing order (continuous longitudes)."""

    lon_deg: np.ndarray
    lat_deg: np.ndarray


def _cut(lon: np.ndarray, lat: np.ndarray, cum: np.ndarray, d: float) -> tuple[float, float]:
    j = int(np.clip(np.searchsorted(cum, d, side="right") - 1, 0, lon.size - 2))
    az, _ = inverse(lon[j], lat[j], lon[j + 1], lat[j + 1])
    plon, plat = direct(lon[j], lat[j], az, d - cum[j])
    return float(plon), float(plat)


def lane_approaches(dep: Port, arr: Port, approach_m: float, with_dep: bool = True,
                    with_arr: bool = True) -> tuple[Approach | None, Approach | None]:
    """Departure and arrival approaches cut from the sea lane between two ports."""
    if approach_m <= 0 or not (with_dep or with_arr):
        return None, None
    coords = _searoute_coords(round(float(wrap_lon(dep.lon_deg)), 4), round(dep.lat_deg, 4),
                              round(float(wrap_lon(arr.lon_deg)), 4), round(arr.lat_deg, 4))
    if coords is None or coords.shape[0] < 2:
        return None, None
    lon = np.unwrap(np.concatenate([[dep.lon_deg], coords[:, 0], [arr.lon_deg]]), period=360.0)
    lon = lon - lon[0] + dep.lon_deg
    lat = np.concatenate([[dep.lat_deg], coords[:, 1], [arr.lat_deg]])
    lon[-1] = unwrap_near(arr.lon_deg, lon[-2])
    _, seg = inverse(lon[:-1], lat[:-1], lon[1:], lat[1:])
    cum = np.concatenate([[0.0], np.cumsum(seg)])
    if cum[-1] < 4.0 * approach_m:
        return None, None
    out_dep = out_arr = None
    if with_dep:
        e = _cut(lon, lat, cum, approach_m)
        k = cum < approach_m
        out_dep = Approach(np.append(lon[k], e[0]), np.append(lat[k], e[1]))
    if with_arr:
        s = _cut(lon, lat, cum, cum[-1] - approach_m)
        k = cum > cum[-1] - approach_m
        out_arr = Approach(np.insert(lon[k], 0, s[0]), np.insert(lat[k], 0, s[1]))
    return out_dep, out_arr


def approach_length_m(ap: Approach | None) -> float:
    """Length [m] of an approach polyline (0 for none)."""
    if ap is None:
        return 0.0
    return float(np.sum(inverse(ap.lon_deg[:-1], ap.lat_deg[:-1], ap.lon_deg[1:],
                                ap.lat_deg[1:])[1]))


def sail_approach(env: Environment, ap: Approach, rpm: float, t0_s: float,
                  limits: RouteLimits) -> RouteEvaluation:
    """Sail an approach at constant `rpm` from `t0_s` (no land check, no RTA)."""
    problem = RouteProblem(float(ap.lon_deg[0]), float(ap.lat_deg[0]), float(ap.lon_deg[-1]),
                           float(ap.lat_deg[-1]), t0_s, t0_s + 30 * 86400.0, limits)
    return sail_tracks(problem, env, None, ap.lon_deg[None, :], ap.lat_deg[None, :],
                       np.array([[rpm]]))
