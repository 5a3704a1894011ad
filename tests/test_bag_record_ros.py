"""``shiproute bag record`` records a live topic into a bag that rosbags and mcap both open,
and closes it properly when stopped with SIGINT."""

from __future__ import annotations

import sys
import time
from pathlib import Path

import pytest
import rosproc

from shiproute_core import topics

pytestmark = pytest.mark.ros


def test_record_live_replay_then_sigint(tmp_path: Path):
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory
    from rclpy.executors import SingleThreadedExecutor
    from rclpy.node import Node
    from rosbags.highlevel import AnyReader
    from shiproute_ais_replay.bag.bagwriter import BagWriter
    from shiproute_ais_replay.bag.shipstate import ShipStateRecord, to_rosbags
    from shiproute_ais_replay.bag.typestore import SHIP_STATE_TYPE, build_typestore
    from std_srvs.srv import SetBool

    t0 = 1_772_668_800 * 10**9
    store = build_typestore()
    src = tmp_path / "src"
    with BagWriter(src, store) as w:
        w.add_topic(topics.SHIP_STATE, SHIP_STATE_TYPE)
        for i in range(200):
            rec = ShipStateRecord(t0 + i * 10**9, 30.0 + 1e-3 * i, 140.0, shaft_rpm=70.0 + i)
            w.write_message(topics.SHIP_STATE, rec.time_ns, to_rosbags(store, rec))
    out = tmp_path / "recorded"
    dom = rosproc.random_domain_id()
    replay = rosproc.RosProcess.script(
        "shiproute_replay_node", "--ros-args", "-p", f"bag:={src}", "-p", "rate:=200.0",
        "-p", "start_paused:=true", domain_id=dom, name="replay")
    record = rosproc.RosProcess([sys.executable, "-u", "-m", "shiproute_ais_replay.cli",
                                 "record", str(out), topics.SHIP_STATE],
                                domain_id=dom, name="record")
    with replay, record, rosproc.ros_context(dom) as ctx:
        record.wait_for_line(r"recording /shiproute/ship_state", 30)
        node = Node("record_test", context=ctx)
        ex = SingleThreadedExecutor(context=ctx)
        ex.add_node(node)
        client = node.create_client(SetBool, "/shiproute_replay/pause")
        rosproc.spin_until(ex, client.service_is_ready, 20, "pause service")
        rosproc.spin_until(
            ex, lambda: node.count_subscribers(topics.SHIP_STATE) > 0, 10, "recorder sub")
        fut = client.call_async(SetBool.Request(data=False))
        rosproc.spin_until(ex, fut.done, 10, "unpause")
        replay.wait_for_line(r"replay finished", 20)
        time.sleep(0.5)  # let the last messages reach the recorder
        assert record.stop() == 0
    assert "recorded 200 messages" in record.output
    assert (out / "metadata.yaml").is_file()
    with AnyReader([out]) as reader:
        msgs = [reader.deserialize(raw, c.msgtype) for c, _, raw in reader.messages()]
    assert [m.shaft_rpm for m in msgs] == [70.0 + i for i in range(200)]
    with (out / "recorded.mcap").open("rb") as f:
        decoded = [m for _, _, _, m in make_reader(
            f, decoder_factories=[DecoderFactory()]).iter_decoded_messages()]
    assert len(decoded) == 200 and decoded[5].latitude_deg == pytest.approx(30.005)
