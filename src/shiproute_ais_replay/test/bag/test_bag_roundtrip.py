"""Bags written by the tools read back with rosbags and with mcap independently."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from ais_replay_helpers import T0_NS, make_states, write_bag
from mcap.reader import make_reader
from mcap_ros2.decoder import DecoderFactory
from rosbags.highlevel import AnyReader
from rosbags.typesys import Stores, get_typestore
from shiproute_ais_replay.bag.bagreader import BagReader
from shiproute_ais_replay.bag.shipstate import ShipStateRecord, from_rosbags
from shiproute_ais_replay.cli import bag_info
from shiproute_core.topics import OWN_FIX, SHIP_STATE


def _same(a: ShipStateRecord, b: ShipStateRecord) -> bool:
    for name in a.__dataclass_fields__:
        x, y = getattr(a, name), getattr(b, name)
        if isinstance(x, float) and math.isnan(x):
            if not math.isnan(y):
                return False
        elif x != y:
            return False
    return True


def test_rosbags_reads_bag_directory_with_embedded_schemas(small_bag):
    path, states = small_bag
    with AnyReader([path], default_typestore=get_typestore(Stores.EMPTY)) as reader:
        # EMPTY default store: the ShipState type can only come from the embedded schema
        conns = {c.topic: c for c in reader.connections}
        assert conns[SHIP_STATE].msgtype == "shiproute_msgs/msg/ShipState"
        got = [from_rosbags(reader.deserialize(raw, c.msgtype))
               for c, _, raw in reader.messages([conns[SHIP_STATE]])]
        fixes = [reader.deserialize(raw, c.msgtype)
                 for c, _, raw in reader.messages([conns[OWN_FIX]])]
    assert len(got) == len(states) == len(fixes)
    assert all(_same(a, b) for a, b in zip(got, states, strict=True))
    assert fixes[10].latitude == states[10].latitude_deg
    assert fixes[10].longitude == states[10].longitude_deg


def test_mcap_ros2_decoder_reads_the_same_messages(small_bag):
    path, states = small_bag
    mcap_file = path / f"{path.name}.mcap"
    with mcap_file.open("rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        summary = reader.get_summary()
        assert summary is not None
        assert {s.name for s in summary.schemas.values()} == {
            "shiproute_msgs/msg/ShipState", "sensor_msgs/msg/NavSatFix"}
        assert all(s.encoding == "ros2msg" for s in summary.schemas.values())
        got = [m for _, _, _, m in reader.iter_decoded_messages(topics=[SHIP_STATE])]
    assert len(got) == len(states)
    for msg, rec in zip(got, states, strict=True):
        assert msg.header.stamp.sec * 10**9 + msg.header.stamp.nanosec == rec.time_ns
        assert (msg.latitude_deg, msg.longitude_deg, msg.sog_kn) == (
            rec.latitude_deg, rec.longitude_deg, rec.sog_kn)
        assert (msg.shaft_rpm, msg.draft_aft_m, msg.mmsi) == (rec.shaft_rpm, 12.0, 211001234)


def test_bare_mcap_file_roundtrip(tmp_path: Path):
    states = make_states(50)
    path = write_bag(tmp_path / "bare.mcap", states, with_fix=False)
    assert path.is_file() and not (tmp_path / "metadata.yaml").exists()
    reader = BagReader(path)
    got = [from_rosbags(reader.deserialize(m)) for m in reader.messages()]
    assert all(_same(a, b) for a, b in zip(got, states, strict=True))
    assert reader.topics()[0].count == 50
    with AnyReader([path]) as ar:  # rosbags opens bare .mcap files too
        assert sum(1 for _ in ar.messages()) == 50


def test_info_reports_topics_counts_and_span(small_bag):
    path, _ = small_bag
    info = bag_info(path)
    assert info["message_count"] == 400
    assert {t["name"]: t["count"] for t in info["topics"]} == {
        SHIP_STATE: 200, OWN_FIX: 200}
    assert info["duration_s"] == pytest.approx(199.0)
    assert info["start"] == "2023-11-14T22:13:20Z"
    assert info["size_bytes"] > 0


def test_reader_start_time_skips_earlier_messages(tmp_path: Path):
    states = make_states(1000)
    path = write_bag(tmp_path / "b", states, chunk_bytes=4000, with_fix=False)
    reader = BagReader(path)
    got = [m.time_ns for m in reader.messages(start_ns=T0_NS + 600 * 10**9)]
    assert got == [s.time_ns for s in states[600:]]


def test_topic_with_offered_qos_reads_back_in_rosbags(tmp_path: Path):
    from shiproute_ais_replay.bag.bagwriter import BagWriter, qos_yaml
    from shiproute_ais_replay.bag.shipstate import to_rosbags
    from shiproute_ais_replay.bag.typestore import SHIP_STATE_TYPE, build_typestore

    store = build_typestore()
    states = make_states(3)
    with BagWriter(tmp_path / "q", store) as w:
        w.add_topic("/latched", SHIP_STATE_TYPE, qos_yaml("reliable", "transient_local", 1))
        for rec in states:
            w.write_message("/latched", rec.time_ns, to_rosbags(store, rec))
    with AnyReader([tmp_path / "q"]) as reader:
        (conn,) = reader.connections
        assert conn.ext.offered_qos_profiles[0].durability.name == "TRANSIENT_LOCAL"
        assert sum(1 for _ in reader.messages()) == 3
