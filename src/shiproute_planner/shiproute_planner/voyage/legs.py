"""The legs of a voyage as the schedule sees them: sea-lane distance per leg (searoute's
shortest sea lane, which goes round continents where the great circle cannot), canal legs at
their transit speed, and the port call at each leg's end."""

from __future__ import annotations

import functools
import itertools
from collections.abc import Sequence
from typing import Any

import numpy as np
from shiproute_core.geodesy import inverse

from ..geo.ports import Port
from ..geo.sea_lanes import lane_between_points, sea_lane_between
from ..route_check import M_PER_NM
from .port_calls import PortCall
from .schedule import FuelRate, LegSpec, fuel_rate_of

KNOT_M_S = M_PER_NM / 3600.0


CAPE_CLIP_SHARE = 0.02  # a great circle this little on land clips a cape: 12 h stages round it


def turns_to_round(land: Any, lon0: float, lat0: float, lon1: float, lat1: float) -> int:
    """Capes and straits a leg must round: the sea lane's turns when the great circle between
    the leg's ends runs over land for more than CAPE_CLIP_SHARE of its length, else 0 (the
    open sea needs no extra stages; the Tsugaru Strait -> Long Beach circle clips Cape Erimo
    for ~0.1 % of its way, and counting its lane's 7 turns gave the crossing 7.3-hour
    stages and 3 % more fuel at equal evaluations)."""
    from shiproute_core.geodesy import great_circle_points

    d = float(inverse(lon0, lat0, lon1, lat1)[1])
    n = int(min(2000, max(8, d / 5000.0)))  # a sample every ~5 km
    lon, lat = great_circle_points(lon0, lat0, lon1, lat1, n)
    inner = slice(1, -1)  # the ends are the approaches' sea ends (or ports)
    if np.mean(land.is_land(np.asarray(lon)[inner], np.asarray(lat)[inner])) <= CAPE_CLIP_SHARE:
        return 0
    return lane_turns(round(lon0, 4), round(lat0, 4), round(lon1, 4), round(lat1, 4))


@functools.lru_cache(maxsize=256)
def lane_turns(lon0: float, lat0: float, lon1: float, lat1: float,
               tolerance_deg: float = 0.1, min_turn_deg: float = 20.0) -> int:
    """Turns of the shortest sea lane between two points: vertices of the lane simplified to
    `tolerance_deg` (~6 NM) where it turns by more than `min_turn_deg`, i.e. the capes and
    straits a route must round (a great circle drawn in lon/lat bends, it does not turn)."""
    import shapely

    lane = _sea_lane(lon0, lat0, lon1, lat1)
    if lane is None or lane.shape[0] < 3:  # no lane known: nothing to round
        return 0
    c = lane.copy()
    c[:, 0] = np.unwrap(c[:, 0], period=360.0)
    simple = np.asarray(shapely.simplify(shapely.LineString(c), tolerance_deg,
                                         preserve_topology=False).coords)
    if simple.shape[0] < 3:
        return 0
    x, y = simple[:-1], simple[1:]
    course = np.degrees(np.arctan2((y[:, 0] - x[:, 0]) * np.cos(np.radians(x[:, 1])),
                                   y[:, 1] - x[:, 1]))
    turn = np.abs((np.diff(course) + 180.0) % 360.0 - 180.0)
    return int(np.sum(turn > min_turn_deg))


def _sea_lane(lon0: float, lat0: float, lon1: float, lat1: float) -> np.ndarray | None:
    """searoute's lane between two points as (k, 2) lon/lat rows, or None where it has none
    (the callers fall back on the great circle)."""
    c = sea_lane_between(lon0, lat0, lon1, lat1)
    return c if c is not None and c.ndim == 2 and c.shape[0] >= 2 else None


@functools.lru_cache(maxsize=256)
def sea_distance_m(lon0: float, lat0: float, lon1: float, lat1: float) -> float:
    """Length of the shortest sea lane between two points [m] (great circle if none), the
    lane cut at its points nearest the two (`lane_between_points`: searoute ends it at the
    network nodes nearest them, which may lie beyond a point in open water, e.g. a shoal
    passage's gate, and the way there and back would count)."""
    direct = float(inverse(lon0, lat0, lon1, lat1)[1])
    c = _sea_lane(lon0, lat0, lon1, lat1)
    if c is None:
        return direct
    c = lane_between_points(c, lon0, lat0, lon1, lat1)
    lon = np.concatenate([[lon0], c[:, 0], [lon1]])
    lat = np.concatenate([[lat0], c[:, 1], [lat1]])
    return max(float(np.sum(inverse(lon[:-1], lat[:-1], lon[1:], lat[1:])[1])), direct)


HOP_SAMPLE_M = 2.0 * M_PER_NM  # a ship's hop onto the sea lane is tested for land this often
HOP_TRIES = 12  # joins tried, shortest first, before the lane as searoute gives it is taken


def sea_distance_under_way_m(land: Any, lon0: float, lat0: float, lon1: float,
                             lat1: float) -> float:
    """Length [m] of the way from a ship at sea (lon0, lat0) to (lon1, lat1): a straight hop
    over open water onto the shortest sea lane, joined where hop and rest of the lane are
    shortest. searoute snaps a position at sea to its network's nearest node, which may lie
    behind the ship: a ship at 39.71N 136.65E bound for the Tsugaru Strait got a lane via
    41.77N 135.96E, 315 NM for 183 NM of open water, and a schedule that had it dawdle
    to the strait and meet cycle 2's storm beyond it."""
    from shiproute_core.geodesy import great_circle_points, unwrap_near

    direct = float(inverse(lon0, lat0, lon1, lat1)[1])
    c = _sea_lane(lon0, lat0, lon1, lat1)
    if c is None:
        return direct
    lon = np.unwrap(np.concatenate([c[:, 0], [lon1]]), period=360.0)
    lon = lon - np.round((lon[0] - unwrap_near(lon[0], lon0)) / 360.0) * 360.0
    lat = np.concatenate([c[:, 1], [lat1]])
    seg = np.atleast_1d(inverse(lon[:-1], lat[:-1], lon[1:], lat[1:])[1])
    rest = np.concatenate([np.cumsum(seg[::-1])[::-1], [0.0]])  # lane from point i on
    hop = np.atleast_1d(inverse(np.full(lon.size, lon0), np.full(lon.size, lat0), lon, lat)[1])
    total = hop + rest
    for i in np.argsort(total, kind="stable")[:HOP_TRIES]:
        n = int(max(2, np.ceil(hop[i] / HOP_SAMPLE_M) + 1))
        h_lon, h_lat = great_circle_points(lon0, lat0, float(lon[i]), float(lat[i]), n)
        if not np.any(land.is_land(np.asarray(h_lon), np.asarray(h_lat))):
            return max(float(total[i]), direct)
    return max(float(hop[0] + rest[0]), direct)  # the lane as searoute gives it


def calm_fuel_rate(model: Any, rpm_min: float, rpm_max: float) -> FuelRate:
    """The ship model's calm-water fuel rate over its RPM range, fitted for the schedule."""
    from ..ship import SeaState

    def speed_fuel(rpm: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        perf = model.evaluate(rpm, np.zeros_like(rpm), SeaState.calm(rpm.size))
        return np.asarray(perf.stw_m_s, float), np.asarray(perf.fuel_t_per_h, float)

    return fuel_rate_of(speed_fuel, rpm_min, rpm_max)


def leg_specs(ports: Sequence[Port], calls: dict[int, PortCall],
              canal_legs: dict[int, Any], land: Any = None) -> list[LegSpec]:
    """One LegSpec per leg ports[k] -> ports[k+1]; `calls` maps an end-port index of `ports`
    to its call, `canal_legs` a leg index to (canal, reversed). With `land` the first port
    is a ship at sea (a re-plan under way), which joins the sea lane where it is shortest
    (`sea_distance_under_way_m`)."""
    from shiproute_planner.route.canals import canal_line

    out = []
    for k, (a, b) in enumerate(itertools.pairwise(ports)):
        call = calls.get(k + 1)
        earliest, latest, berth = ((None, None, 0.0) if call is None
                                   else (call.earliest_s, call.latest_s, call.berth_s))
        if k in canal_legs:
            canal, rev = canal_legs[k]
            lon, lat = canal_line(canal, rev)
            length = float(np.sum(inverse(lon[:-1], lat[:-1], lon[1:], lat[1:])[1]))
            out.append(LegSpec(b.name, length, length / (canal.transit_kn * KNOT_M_S),
                               earliest, latest, berth))
            continue
        ends = (round(a.lon_deg, 4), round(a.lat_deg, 4), round(b.lon_deg, 4),
                round(b.lat_deg, 4))
        d = (sea_distance_under_way_m(land, *ends) if k == 0 and land is not None
             else sea_distance_m(*ends))
        out.append(LegSpec(b.name, d, None, earliest, latest, berth))
    return out


def cube_law_rate(v_min_m_s: float = 4.0, v_max_m_s: float = 12.0) -> FuelRate:
    """A fuel rate proportional to speed cubed (propeller law) for models without a
    calm-water evaluation: the schedule's shape without the ship's numbers."""
    return FuelRate(v_min_m_s, v_max_m_s, (0.05, 0.0, 0.0, 0.0))


def voyage_schedule(ports: Sequence[Port], calls: dict[int, PortCall],
                    canal_legs: dict[int, Any], depart_s: float, rta_s: float, model: Any,
                    rpm_min: float, rpm_max: float, under_way_land: Any = None
                    ) -> tuple[list[LegSpec], Any, list[str], FuelRate]:
    """(legs, Schedule, notes, fuel rate): the fuel-optimal schedule of a multi-port voyage
    (the rate re-schedules the legs left as each leg is planned); `under_way_land` (the
    land mask) when the voyage starts at a ship at sea."""
    from .schedule import plan_schedule

    notes: list[str] = []
    try:
        rate = calm_fuel_rate(model, rpm_min, rpm_max)
    except Exception as exc:  # a model without calm-water evaluation: say so, use the law
        rate = cube_law_rate()
        notes.append(f"leg schedule estimated with the propeller (cube) law: the ship model "
                     f"gives no calm-water fuel rate ({exc})")
    legs = leg_specs(ports, calls, canal_legs, under_way_land)
    return legs, plan_schedule(legs, depart_s, rta_s, rate), notes, rate
