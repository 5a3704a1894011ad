"""A coastal passage takes the deep-water route off a wide shoal before it gives up the
ship's depth limit (the corridor round the sea lane is widened first), and keeps to water
known deep enough rather than a coarse grid's smeared coastal band."""

from __future__ import annotations

import numpy as np
from shiproute_core.geodesy import densify_track
from shiproute_core.units import M_PER_NM
from shiproute_planner.geo.bathymetry import DepthGrid
from shiproute_planner.geo.depth import Bathymetry
from shiproute_planner.geo.gshhg import LandPolygons
from shiproute_planner.route.passages import PassageRules, compute_passage

LAT0 = 10.0
NM_LON = 1.0 / 60.0 / np.cos(np.radians(LAT0))  # degrees of longitude per NM at LAT0
NM_LAT = 1.0 / 60.0
CELL_DEG = 1.0 / 120.0  # a 30 arc-second grid, as GEBCO's older releases


def _far_island() -> LandPolygons:
    """One small island 40 NM off the lane: land data for the grid, never in the way."""
    ring = np.array([[-0.8, LAT0 - 0.45], [-0.7, LAT0 - 0.45], [-0.7, LAT0 - 0.4],
                     [-0.8, LAT0 - 0.4]])
    return LandPolygons("test", ring, np.array([0]), np.array([4]),
                        np.array([[-0.8, LAT0 - 0.45, -0.7, LAT0 - 0.4]]))


def _bank(east_edge_nm: float) -> Bathymetry:
    """40 m everywhere but an 8 m bank 12 NM long (north-south) across the lane, from far
    west to `east_edge_nm` east of it: the only deep way round is its east end."""
    lat = np.arange(LAT0 - 0.9, LAT0 + 0.9, CELL_DEG)
    lon = np.arange(-1.2, 1.2, CELL_DEG)
    depth = np.full((lat.size, lon.size), 40.0, dtype=np.float32)
    rows = np.abs(lat - LAT0) <= 6.0 * NM_LAT
    cols = lon <= east_edge_nm * NM_LON
    depth[np.ix_(rows, cols)] = 8.0
    return Bathymetry([DepthGrid("bank", depth, float(lat[0]), CELL_DEG, float(lon[0]),
                                 CELL_DEG, False)])


def test_a_bank_wider_than_the_corridor_is_passed_round_in_a_wider_one():
    lane_lon = np.array([0.0, 0.0])
    lane_lat = np.array([LAT0 - 0.35, LAT0 + 0.35])  # 42 NM north, the bank in the middle
    bathy = _bank(east_edge_nm=12.0)  # reaches past a 10 NM corridor, not past 30 NM
    rules = PassageRules(required_depth_m=14.0, bathymetry=bathy, corridors_nm=(10.0, 30.0))
    p = compute_passage(lane_lon, lane_lat, rules, polygons=_far_island())
    assert p is not None
    assert p.depth_limited and p.corridor_nm == 30.0
    d_lon, d_lat = (np.asarray(v) for v in densify_track(p.lon_deg, p.lat_deg,
                                                         0.05 * M_PER_NM))
    # the bank as built: every point of the passage north of the berth and pilotage waters
    # is on 40 m, and the passage crosses the bank's latitudes east of its end
    assert np.min(bathy.depth_m(d_lon, d_lat)) >= 14.0
    over = np.abs(d_lat - LAT0) <= 6.0 * NM_LAT
    assert over.any() and np.all(d_lon[over] > 12.0 * NM_LON)


def test_with_no_deep_way_in_any_corridor_the_limit_is_dropped_and_the_lane_kept_close():
    lane_lon = np.array([0.0, 0.0])
    lane_lat = np.array([LAT0 - 0.35, LAT0 + 0.35])
    bathy = _bank(east_edge_nm=60.0)  # past every corridor: no deep way within 30 NM
    rules = PassageRules(required_depth_m=14.0, bathymetry=bathy, corridors_nm=(10.0, 30.0))
    p = compute_passage(lane_lon, lane_lat, rules, polygons=_far_island())
    assert p is not None and not p.depth_limited  # said by the plan (coastal_passages)
    assert np.max(np.abs(p.lon_deg)) < 0.25 * NM_LON  # straight on, as without a limit


def test_a_deep_draft_passage_leaves_the_coarse_coastal_band_for_known_deep_water():
    # coast: land west of 0.2 W; a 5 arc-minute grid reads 40 m everywhere, so its cells
    # within 1.5 cells (7.5 NM) of the coast give no depth (the band of unknown depth);
    # the lane runs in that band 3 NM off the coast
    land = _box_land(-0.8, LAT0 - 0.5, -0.2, LAT0 + 0.5)
    coarse = 1.0 / 12.0
    lat = np.arange(LAT0 - 0.9, LAT0 + 0.9, coarse)
    lon = np.arange(-1.2, 1.2, coarse)
    bathy = Bathymetry([DepthGrid("coarse", np.full((lat.size, lon.size), 40.0, np.float32),
                                  float(lat[0]), coarse, float(lon[0]), coarse, False)])
    lane_lon = np.full(2, -0.2 + 3 * NM_LON)
    lane_lat = np.array([LAT0 - 0.3, LAT0 + 0.3])  # 36 NM north along the coast
    rules = PassageRules(required_depth_m=14.0, bathymetry=bathy, berth_nm=1.0,
                         pilotage_nm=2.0, corridors_nm=(10.0,))
    p = compute_passage(lane_lon, lane_lat, rules, polygons=land)
    assert p is not None and p.depth_limited
    d_lon, d_lat = (np.asarray(v) for v in densify_track(p.lon_deg, p.lat_deg,
                                                         0.1 * M_PER_NM))
    off_coast_nm = (d_lon + 0.2) / NM_LON
    # the middle half of the passage (well clear of the pilotage waters at its ends) runs
    # where the grid decides: farther off the coast than 1.5 cells (7.5 NM)
    middle = np.abs(d_lat - LAT0) < 0.15
    assert middle.any() and np.all(off_coast_nm[middle] > 7.5)


def _box_land(lon0: float, lat0: float, lon1: float, lat1: float) -> LandPolygons:
    ring = np.array([[lon0, lat0], [lon1, lat0], [lon1, lat1], [lon0, lat1]])
    return LandPolygons("test", ring, np.array([0]), np.array([4]),
                        np.array([[lon0, lat0, lon1, lat1]]))
