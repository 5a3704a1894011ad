"""Port approaches: the voyage leaves and reaches its ports along the sea lane.

Harbours, estuaries and straits near a port (Busan's harbour, the Tsugaru Strait, Long Beach
behind the Channel Islands) cannot be threaded by straight 12-hour legs. The planner therefore
optimises between the sea ends of the approaches and sails the approaches themselves along
the `searoute` lane at a fixed RPM (coastal waters: not land-checked, the lane's own geometry
is trusted). An approach is at least `approach_m` long and, with a `CoastalPassage` rule,
runs on until the great circle from its end to the other approach's end is clear of land:
ocean routing starts where the coastal passage (straits, capes, island chains next to the
port) ends, and the optimised part has a land-free straight route.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from shiproute_core.geodesy import direct, inverse, unwrap_near
from shiproute_core.units import M_PER_NM

from ..geo.landmask import LandMask
from ..geo.ports import Port
from ..geo.sea_lanes import sea_lane_between
from ..geo.verify import densify_track
from .approach_shoals import ShoalLimit, end_past_shoals
from .environment import Environment
from .evaluation import RouteEvaluation
from .problem import RouteLimits, RouteProblem
from .sail_fixed_point import sail_track


@dataclass(frozen=True)
class Approach:
    """A polyline in sailing order (continuous longitudes) and what the plan must say
    about where it ends."""

    lon_deg: np.ndarray
    lat_deg: np.ndarray
    notes: tuple[str, ...] = ()
    # run on past a shoal next to the port: the approach to sail instead when its computed
    # passage finds no way round the shoal in water deep enough (`coastal_passages`)
    fallback: Approach | None = None


@dataclass(frozen=True)
class CoastalPassage:
    """Where approaches end: at the first lane point (from the port outwards, within the
    first `share` of the lane) from which the great circle to the other approach's end is
    clear of land; candidates every `step_m`. With `shoals` (a ship with a depth limit)
    no nearer the port than past the lane's shoals next to it (`approach_shoals`)."""

    land: LandMask
    share: float = 1.0 / 6.0
    step_m: float = 5.0 * M_PER_NM
    # when no two ends see each other: how far along the lane an end must see over open sea
    ahead_m: float = 100.0 * M_PER_NM
    shoals: ShoalLimit | None = None


def _points_at(lon: np.ndarray, lat: np.ndarray, cum: np.ndarray,
               d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Points at lane distances `d` [m] (geodesic interpolation within lane segments)."""
    j = np.clip(np.searchsorted(cum, d, side="right") - 1, 0, lon.size - 2)
    az, _ = inverse(lon[j], lat[j], lon[j + 1], lat[j + 1])
    p_lon, p_lat = direct(lon[j], lat[j], az, d - cum[j])
    return np.asarray(p_lon, dtype=float), np.asarray(p_lat, dtype=float)


def _clear_sight_m(lon: np.ndarray, lat: np.ndarray, cum: np.ndarray, far: tuple[float, float],
                   rule: CoastalPassage, min_m: float) -> float:
    """First lane distance >= min_m from which the great circle to `far` misses land
    (min_m if none within the first `share` of the lane)."""
    d = np.arange(min_m, max(rule.share * cum[-1], min_m) + 1.0, rule.step_m)
    p_lon, p_lat = _points_at(lon, lat, cum, d)
    far_lon = np.full(d.size, unwrap_near(far[0], float(p_lon[0])))
    hits = rule.land.segment_land_samples(p_lon, p_lat, far_lon, np.full(d.size, far[1]))
    clear = np.flatnonzero(hits == 0)
    return float(d[clear[0]]) if clear.size else min_m


#: coastal ends found per (lane, rule, minimums): re-plans of a ship that has not moved (a new
#: forecast cycle at the berth) meet the same lane again; the search costs ~50 ms
_ENDS_MEMO: dict[tuple, tuple[float, float]] = {}
_ENDS_MEMO_MAX = 64


def _coastal_ends(lon: np.ndarray, lat: np.ndarray, cum: np.ndarray, rule: CoastalPassage,
                  min_dep_m: float, min_m: float) -> tuple[float, float]:
    """Departure and arrival approach lengths [m] whose ends see each other over open sea
    (`_search_coastal_ends`, memoised: the answer depends on the lane and the land only)."""
    key = (lon.tobytes(), lat.tobytes(), rule.land.resolution, rule.land.cell_deg, rule.share,
           rule.step_m, rule.ahead_m,
           float(min_dep_m), float(min_m))
    ends = _ENDS_MEMO.get(key)
    if ends is None:
        ends = _search_coastal_ends(lon, lat, cum, rule, min_dep_m, min_m)
        if len(_ENDS_MEMO) >= _ENDS_MEMO_MAX:
            _ENDS_MEMO.clear()
        _ENDS_MEMO[key] = ends
    return ends


def _search_coastal_ends(lon: np.ndarray, lat: np.ndarray, cum: np.ndarray,
                         rule: CoastalPassage, min_dep_m: float, min_m: float
                         ) -> tuple[float, float]:
    """Departure and arrival approach lengths [m] whose ends see each other over open sea:
    alternately the shortest one end can be with the other fixed, starting from the arrival
    end at its farthest; when no such pair exists, each end where it first sees the lane's
    middle (the minimum where it does not)."""
    r_lon, r_lat, r_cum = lon[::-1], lat[::-1], cum[-1] - cum[::-1]

    def end(lo: np.ndarray, la: np.ndarray, cu: np.ndarray, d: float) -> tuple[float, float]:
        p = _points_at(lo, la, cu, np.array([d]))
        return float(p[0][0]), float(p[1][0])

    d_arr = max(rule.share * cum[-1], min_m)
    d_dep = min_dep_m
    for _ in range(2):
        d_dep = _clear_sight_m(lon, lat, cum, end(r_lon, r_lat, r_cum, d_arr), rule, min_dep_m)
        d_arr = _clear_sight_m(r_lon, r_lat, r_cum, end(lon, lat, cum, d_dep), rule, min_m)
    # the dense check (geodesic points every 500 m on the polygons) has the last word: the
    # end nearer a point it finds on land moves on by a step, a few times at most
    for _ in range(12):
        a, b = end(lon, lat, cum, d_dep), end(r_lon, r_lat, r_cum, d_arr)
        p_lon, p_lat = densify_track(np.array([a[0], unwrap_near(b[0], a[0])]),
                                     np.array([a[1], b[1]]), 500.0)
        hit = np.flatnonzero(rule.land.is_land(p_lon, p_lat))
        if hit.size == 0:
            return d_dep, d_arr
        if hit.mean() < 0.5 * p_lon.size:
            d_dep += rule.step_m
        else:
            d_arr += rule.step_m
    # no pair sees each other (both ports deep in inner waters: Anchorage up Cook Inlet,
    # Vancouver behind Vancouver Island): each end goes out to where it sees the lane ahead
    # over open sea, so neither span seam cuts across the islands round its port
    return (_sees_ahead_m(lon, lat, cum, rule, min_dep_m),
            _sees_ahead_m(r_lon, r_lat, r_cum, rule, min_m))


def _sees_ahead_m(lon: np.ndarray, lat: np.ndarray, cum: np.ndarray, rule: CoastalPassage,
                  min_m: float) -> float:
    """First lane distance >= min_m from which the great circle to the lane point
    `rule.ahead_m` further on (at most the lane's middle) misses land (min_m if none within
    the first `share` of the lane)."""
    d = np.arange(min_m, max(rule.share * cum[-1], min_m) + 1.0, rule.step_m)
    p_lon, p_lat = _points_at(lon, lat, cum, d)
    f_lon, f_lat = _points_at(lon, lat, cum, np.minimum(d + rule.ahead_m, 0.5 * cum[-1]))
    ahead = d + rule.step_m < 0.5 * cum[-1]
    hits = rule.land.segment_land_samples(p_lon, p_lat, f_lon, f_lat)
    clear = np.flatnonzero((hits == 0) & ahead)
    return float(d[clear[0]]) if clear.size else min_m


def lane_approaches(dep: Port, arr: Port, approach_m: float, with_dep: bool = True,
                    with_arr: bool = True, coastal: CoastalPassage | None = None,
                    dep_min_m: float | None = None) -> tuple[Approach | None, Approach | None]:
    """Departure and arrival approaches cut from the sea lane between two ports: at least
    `approach_m` long (the departure one `dep_min_m`, e.g. 0 for a ship under way) and, with
    `coastal`, on until the great circle between their ends clears the land (through the
    straits and past the capes next to each port). None for an approach of zero length."""
    if approach_m <= 0 or not (with_dep or with_arr):
        return None, None
    coords = sea_lane_between(dep.lon_deg, dep.lat_deg, arr.lon_deg, arr.lat_deg)
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
    d_arr = approach_m
    d_dep = approach_m if dep_min_m is None else dep_min_m
    if coastal is not None:
        d_dep, d_arr = _coastal_ends(lon, lat, cum, coastal, d_dep, d_arr)
    out_dep = _departure(lon, lat, cum, d_dep) if with_dep else None
    out_arr = _arrival(lon, lat, cum, d_arr) if with_arr else None
    if coastal is None or coastal.shoals is None:
        return out_dep, out_arr
    # past the shoals next to each port: walked from the minimums, the ends searched again
    limit = coastal.share * cum[-1]
    m_dep = approach_m if dep_min_m is None else dep_min_m
    w_dep, said_dep = end_past_shoals(lambda d: _points_at(lon, lat, cum, d), float(cum[-1]),
                                      m_dep, limit, coastal.shoals,
                                      f"departure from {dep.name}") if with_dep else (m_dep, ())
    r_lon, r_lat, r_cum = lon[::-1], lat[::-1], cum[-1] - cum[::-1]
    w_arr, said_arr = end_past_shoals(lambda d: _points_at(r_lon, r_lat, r_cum, d),
                                      float(cum[-1]), approach_m, limit, coastal.shoals,
                                      f"arrival at {arr.name}") if with_arr else (approach_m, ())
    if not (said_dep or said_arr):
        return out_dep, out_arr
    e_dep, e_arr = _coastal_ends(lon, lat, cum, coastal, w_dep, w_arr)
    if with_dep:
        out_dep = _departure(lon, lat, cum, e_dep, said_dep,
                             out_dep if w_dep > m_dep and e_dep != d_dep else None)
    if with_arr:
        out_arr = _arrival(lon, lat, cum, e_arr, said_arr,
                           out_arr if w_arr > approach_m and e_arr != d_arr else None)
    return out_dep, out_arr


def _departure(lon: np.ndarray, lat: np.ndarray, cum: np.ndarray, d_m: float,
               notes: tuple[str, ...] = (), fallback: Approach | None = None
               ) -> Approach | None:
    """The lane's first `d_m` [m] as a departure approach (None for none)."""
    if d_m <= 0:
        return None
    e_lon, e_lat = _points_at(lon, lat, cum, np.array([d_m]))
    k = cum < d_m
    return Approach(np.append(lon[k], e_lon), np.append(lat[k], e_lat), notes, fallback)


def _arrival(lon: np.ndarray, lat: np.ndarray, cum: np.ndarray, d_m: float,
             notes: tuple[str, ...] = (), fallback: Approach | None = None) -> Approach:
    """The lane's last `d_m` [m] as an arrival approach."""
    s_lon, s_lat = _points_at(lon, lat, cum, np.array([cum[-1] - d_m]))
    k = cum > cum[-1] - d_m
    return Approach(np.concatenate([s_lon, lon[k]]), np.concatenate([s_lat, lat[k]]), notes,
                    fallback)


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
    return sail_track(problem, env, None, ap.lon_deg, ap.lat_deg, np.array([rpm]))
