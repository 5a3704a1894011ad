"""ROS-free helpers of the planner node: ECEF path frame, re-plan triggers, cycle assembly."""

import numpy as np
import pytest
from shiproute_planner.path_frame import ecef_to_lat_lon, heading_from_quaternion, track_to_ecef
from shiproute_planner.ros.cycle_assembler import CycleAssembler
from shiproute_planner.ros.replan_policy import ReplanThresholds, track_deviation


def test_ecef_origin_point_is_the_semi_major_axis():
    poses = track_to_ecef([0.0], [0.0], [0.0])
    # WGS 84: a = 6,378,137 m exactly; (lat 0, lon 0) lies on the +x axis.
    assert poses.x_m[0] == pytest.approx(6378137.0, abs=1e-6)
    assert abs(poses.y_m[0]) < 1e-6 and abs(poses.z_m[0]) < 1e-6


def test_ecef_round_trip_is_lossless_including_antimeridian_and_poles():
    lat = np.array([35.08, 33.694, 0.0, -60.0, 89.9, 51.0])
    lon = np.array([129.112, -118.251, 179.999, -179.999, 10.0, 180.0])
    heading = np.array([45.0, 270.0, 0.0, 359.5, 123.0, 181.0])
    poses = track_to_ecef(lat, lon, heading)
    lat2, lon2 = ecef_to_lat_lon(poses.x_m, poses.y_m, poses.z_m)
    assert np.abs(lat2 - lat).max() < 1e-9  # ~0.1 mm
    assert np.abs((lon2 - lon + 180.0) % 360.0 - 180.0).max() < 1e-9
    back = heading_from_quaternion(lat, lon, poses.quaternion_xyzw)
    assert np.abs((back - heading + 180.0) % 360.0 - 180.0).max() < 1e-9
    assert np.allclose(np.linalg.norm(poses.quaternion_xyzw, axis=1), 1.0)


def test_north_heading_at_equator_points_along_ecef_z():
    poses = track_to_ecef([0.0], [0.0], [0.0])
    x, y, z, w = poses.quaternion_xyzw[0]
    bow = np.array([1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)])
    assert np.allclose(bow, [0.0, 0.0, 1.0], atol=1e-12)


def test_cross_track_and_schedule_deviation():
    # Track along the equator from 0E to 2E in 2 h; ship 0.5 deg north of its midpoint.
    dev = track_deviation(
        np.array([0.0, 0.0]), np.array([0.0, 2.0]), np.array([0.0, 7200.0]), 0.5, 1.0, 4500.0
    )
    # WGS 84 meridian arc of 0.5 deg from the equator: 55,287.6 m = 29.853 NM; the track is
    # densified every 2 NM, so the nearest point can be 1 NM along-track off the foot point.
    assert dev.cross_track_nm == pytest.approx(29.853, abs=0.05)
    assert dev.schedule_deviation_s == pytest.approx(900.0, abs=130.0)  # 1 NM of 120 NM in 2 h
    assert dev.along_track_fraction == pytest.approx(0.5, abs=0.02)
    reasons = ReplanThresholds(cross_track_nm=20.0, schedule_s=3600.0).exceeded(dev)
    assert len(reasons) == 1 and "cross-track" in reasons[0]
    assert ReplanThresholds(cross_track_nm=40.0).exceeded(dev) == []


def test_cycle_is_released_only_when_complete_in_any_arrival_order():
    asm: CycleAssembler[str] = CycleAssembler()
    assert asm.add_slice("c1", 2, 3, "s2") is None
    assert asm.add_slice("c1", 0, 3, "s0") is None
    assert asm.missing("c1") is None  # not announced yet
    assert asm.announce("c1", 3) is None
    assert asm.missing("c1") == 1
    assert asm.add_slice("c1", 1, 3, "s1") == ["s0", "s1", "s2"]
    # A repeated (transient-local) delivery of a finished cycle is ignored.
    assert asm.add_slice("c1", 1, 3, "s1") is None
    assert asm.announce("c1", 3) is None
    with pytest.raises(ValueError, match="outside"):
        asm.add_slice("c2", 5, 3, "bad")
