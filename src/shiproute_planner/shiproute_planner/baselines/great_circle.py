"""Great circle (or the sea lane where it touches land) at the constant RPM meeting the RTA."""

from __future__ import annotations

import time

import numpy as np

from ..ga.seeds import sea_lane_track
from ..geo.geodesy import M_PER_NM, great_circle_points
from .inputs import BaselineInputs
from .result import BaselineResult
from .rpm_fit import constant_rpm_for_rta

GC_POINT_SPACING_M = 100 * M_PER_NM


def great_circle_track(inp: BaselineInputs) -> tuple[np.ndarray, np.ndarray, str]:
    """Track lon/lat and its kind ("great_circle" or "sea_lane")."""
    p = inp.problem
    from .geodesy import inverse

    _, dist = inverse(p.dep_lon_deg, p.dep_lat_deg, p.arr_lon_deg, p.arr_lat_deg)
    n = max(int(np.ceil(float(dist) / GC_POINT_SPACING_M)) + 1, 2)
    lon, lat = great_circle_points(p.dep_lon_deg, p.dep_lat_deg, p.arr_lon_deg, p.arr_lat_deg, n)
    sailor = inp.sailor()
    if not sailor.crosses_land(lon[:-1], lat[:-1], lon[1:], lat[1:]).any():
        return lon, lat, "great_circle"
    lane = sea_lane_track(p)
    if lane is None:
        return lon, lat, "great_circle"
    return lane[0], lane[1], "sea_lane"


def run_great_circle(inp: BaselineInputs) -> BaselineResult:
    """Great circle / sea lane at the lowest constant RPM that arrives by the RTA."""
    t0 = time.perf_counter()
    lon, lat, kind = great_circle_track(inp)
    rpm, ev, n_eval = constant_rpm_for_rta(inp.problem, inp.env, inp.land, lon, lat)
    return BaselineResult("great_circle", ev, time.perf_counter() - t0, False,
                          route_evaluations=n_eval, notes=(f"track: {kind}", f"rpm {rpm:.2f}"))
