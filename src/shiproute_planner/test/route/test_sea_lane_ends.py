"""Sea-lane seeds end where the span ends: a lane is cut at its points nearest the stops, so
a span ending at a shoal passage's gate between two far-apart lane nodes does not run on to
the node past the gate (over the shoal) and turn back."""

import numpy as np
import pytest
from shiproute_core.geodesy import inverse
from shiproute_core.units import M_PER_NM
from shiproute_planner.geo.sea_lanes import lane_between_points
from shiproute_planner.route.problem import RouteLimits, RouteProblem
from shiproute_planner.route.seeding import sea_lane_track


def test_lane_is_cut_at_the_points_nearest_the_ends():
    lane = np.array([[0.0, 0.0], [5.0, 0.0], [10.0, 0.0]])
    cut = lane_between_points(lane, 1.0, 0.2, 7.0, -0.3)
    # on the equator the nearest points of the lane are straight below/above the ends
    np.testing.assert_allclose(cut, [[1.0, 0.0], [5.0, 0.0], [7.0, 0.0]], atol=1e-9)


def test_ends_beyond_the_lane_keep_its_end_nodes():
    lane = np.array([[0.0, 0.0], [5.0, 0.0], [10.0, 0.0]])
    cut = lane_between_points(lane, -1.0, 0.5, 11.0, 0.5)
    np.testing.assert_allclose(cut, lane, atol=1e-9)


def test_lane_across_the_antimeridian_is_cut_in_one_frame():
    lane = np.array([[178.0, 10.0], [-178.0, 10.0], [-170.0, 10.0]])
    cut = lane_between_points(lane, 179.0, 10.0, -175.0, 10.0)
    np.testing.assert_allclose(cut, [[179.0, 10.0], [182.0, 10.0], [185.0, 10.0]], atol=1e-9)


def test_span_ending_at_a_gate_does_not_cross_the_shoal_beyond_it():
    pytest.importorskip("searoute")
    # Strait of Magellan's east end -> the gate 30 NM before the 13 m ETOPO5 cell off Bahia
    # Blanca on the lane Valparaiso -> Buenos Aires; searoute's nodes on either side of the
    # gate lie at 43.09 S 63.69 W and 39.30 S 61.25 W, the shoal between the gate and the
    # second one
    gate_lon, gate_lat, shoal_lon, shoal_lat = -62.154, -40.759, -61.807, -40.207
    problem = RouteProblem(-69.466, -52.452, gate_lon, gate_lat, 0.0, 5 * 86400.0,
                           RouteLimits(40.0, 120.0), stage_s=12 * 3600.0, n_stages=8,
                           arr_name="deep-water passage past the shoal at -40.20, -61.80 "
                                    "(13 m on the sea lane) gate")
    lon, lat = sea_lane_track(problem, max_points=400)
    assert lat.max() <= gate_lat + 0.05  # the lane runs north here: nothing beyond the gate
    _, to_shoal = inverse(lon, lat, np.full(lon.size, shoal_lon), np.full(lon.size, shoal_lat))
    gate_to_shoal = float(inverse(gate_lon, gate_lat, shoal_lon, shoal_lat)[1])
    assert to_shoal.min() >= gate_to_shoal - 2.0 * M_PER_NM


def test_schedule_distance_to_a_gate_in_an_estuary_is_not_counted_there_and_back():
    pytest.importorskip("searoute")
    from shiproute_planner.voyage.legs import sea_distance_m

    # Buenos Aires -> the gate of the deep-water passage through the Rio de la Plata: open
    # water all the way, so the sea way is close to the great circle (59 NM); searoute's
    # lane ends at its node 56.50 W 35.10 S, 35 NM past the gate
    ba_lon, ba_lat, gate_lon, gate_lat = -58.363, -34.591, -57.198, -34.831
    direct = float(inverse(ba_lon, ba_lat, gate_lon, gate_lat)[1])
    assert sea_distance_m(ba_lon, ba_lat, gate_lon, gate_lat) <= 1.25 * direct
