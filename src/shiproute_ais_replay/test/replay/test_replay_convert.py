"""NavSatFix -> ShipState conversion (hand-computed speeds) and the rosbags -> rclpy copy."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from ais_replay_helpers import T0_NS, meridian_arc_m
from shiproute_ais_replay.bag.bagwriter import BagWriter
from shiproute_ais_replay.bag.shipstate import NavFixConverter, ShipStateRecord, to_rosbags
from shiproute_ais_replay.bag.typestore import build_typestore
from shiproute_ais_replay.replay.engine import ReplayConfig, ReplayEngine
from shiproute_core.units import M_S_PER_KNOT

# 0.01 deg of latitude north from 10 N on the WGS 84 meridian, in metres (about 1106.1 m)
M_PER_CENTIDEG = meridian_arc_m(10.0, 10.01)
KN = M_S_PER_KNOT


def test_sog_cog_from_consecutive_fixes():
    conv = NavFixConverter(mmsi=7)
    assert math.isnan(conv.feed_fix(0, 10.0, 20.0).sog_kn)  # first fix: unknown
    rec = conv.feed_fix(60 * 10**9, 10.01, 20.0)
    assert rec.sog_kn == pytest.approx(M_PER_CENTIDEG / 60 / KN, rel=1e-7)  # 35.83 kn
    assert rec.cog_deg == pytest.approx(0.0, abs=1e-9)
    assert rec.mmsi == 7


def test_velocity_topic_wins_over_fix_difference():
    conv = NavFixConverter()
    conv.feed_fix(0, 10.0, 20.0)
    conv.feed_velocity(59 * 10**9, 5.0, 0.0)  # 5 m/s east (ENU)
    rec = conv.feed_fix(60 * 10**9, 10.01, 20.0)
    assert rec.sog_kn == pytest.approx(5.0 / KN)
    assert rec.cog_deg == pytest.approx(90.0)


def test_no_fix_status_and_bad_positions_are_rejected():
    conv = NavFixConverter()
    assert conv.feed_fix(0, 10.0, 20.0, status=-1) is None
    assert conv.feed_fix(1, float("nan"), 20.0) is None
    assert conv.feed_fix(2, 95.0, 20.0) is None
    assert conv.rejected == 3
    assert conv.feed_fix(3, 10.0, 200.0).longitude_deg == pytest.approx(-160.0)


def _navsat_bag(path: Path) -> Path:
    store = build_typestore()
    t = store.types
    with BagWriter(path, store) as w:
        w.add_topic("/gps/fix", "sensor_msgs/msg/NavSatFix")
        w.add_topic("/gps/vel", "geometry_msgs/msg/TwistStamped")
        for i in range(5):
            t_ns = T0_NS + i * 10**9
            stamp = t["builtin_interfaces/msg/Time"](sec=t_ns // 10**9, nanosec=0)
            hdr = t["std_msgs/msg/Header"](stamp=stamp, frame_id="gps")
            fix = t["sensor_msgs/msg/NavSatFix"](
                header=hdr, status=t["sensor_msgs/msg/NavSatStatus"](status=0, service=1),
                latitude=10.0 + 0.001 * i, longitude=20.0, altitude=0.0,
                position_covariance=np.zeros(9), position_covariance_type=0)
            w.write_message("/gps/fix", t_ns, fix)
            vec = t["geometry_msgs/msg/Vector3"]
            twist = t["geometry_msgs/msg/Twist"](linear=vec(x=0.0, y=3.0, z=0.0),
                                                 angular=vec(x=0.0, y=0.0, z=0.0))
            w.write_message("/gps/vel", t_ns + 1, t["geometry_msgs/msg/TwistStamped"](
                header=hdr, twist=twist))
    return path


def test_engine_converts_navsatfix_bag_and_passes_topics(tmp_path: Path):
    bag = _navsat_bag(tmp_path / "gps")
    cfg = ReplayConfig(rate=0.0, pass_topics=("/gps/fix",), remap={"/gps/fix": "/fix"})
    engine = ReplayEngine(bag, cfg)
    events = []
    engine.run(events.append, lambda _ns: None)
    states = [e.record for e in events if e.kind == "ship_state_converted"]
    assert [round(s.latitude_deg, 6) for s in states] == [10.0, 10.001, 10.002, 10.003, 10.004]
    assert math.isnan(states[0].sog_kn)
    assert states[2].sog_kn == pytest.approx(3.0 / KN)  # from /gps/vel (north 3 m/s)
    assert states[2].cog_deg == pytest.approx(0.0)
    passed = [e for e in events if e.kind == "pass"]
    assert len(passed) == 5 and {e.topic for e in passed} == {"/fix"}


def test_field_copy_to_rclpy_matches_source():
    from shiproute_ais_replay.ros.convert import rclpy_class, ship_state_to_rclpy, to_rclpy

    store = build_typestore()
    rec = ShipStateRecord(T0_NS + 5, 1.0, 2.0, sog_kn=3.0, shaft_rpm=70.0, mmsi=9, nav_status=5)
    msg = to_rclpy(to_rosbags(store, rec), rclpy_class("shiproute_msgs/msg/ShipState"))
    direct = ship_state_to_rclpy(rec)
    for name in ("latitude_deg", "longitude_deg", "sog_kn", "shaft_rpm", "mmsi", "nav_status"):
        assert getattr(msg, name) == getattr(direct, name) == getattr(rec, name)
    assert math.isnan(msg.cog_deg)
    assert msg.header.stamp.nanosec == 5 and msg.header.frame_id == "wgs84"
