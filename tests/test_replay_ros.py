"""Replay node across processes: timing at 100x, /clock, pause/resume, seek, diagnostics.

The bag is written by the package's own writer; the node runs as a separate process on a
random ROS domain and this process subscribes like any other node would.
"""

from __future__ import annotations

import itertools
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import rosproc

from shiproute_core import topics

pytestmark = pytest.mark.ros

T0_NS = 1_772_668_800 * 10**9
RATE = 100.0


def _write_bag(path: Path, offsets_s: list[float]) -> Path:
    from shiproute_ais_replay.bag.bagwriter import BagWriter
    from shiproute_ais_replay.bag.shipstate import ShipStateRecord, to_rosbags
    from shiproute_ais_replay.bag.typestore import SHIP_STATE_TYPE, build_typestore

    store = build_typestore()
    with BagWriter(path, store) as w:
        w.add_topic(topics.SHIP_STATE, SHIP_STATE_TYPE)
        for i, off in enumerate(offsets_s):
            rec = ShipStateRecord(T0_NS + int(off * 1e9), 30.0, 140.0 + 1e-4 * i, sog_kn=12.0)
            w.write_message(topics.SHIP_STATE, rec.time_ns, to_rosbags(store, rec))
    return path


class Peer:
    """Subscriber/client side in this process."""

    def __init__(self, ctx: Any) -> None:
        from diagnostic_msgs.msg import DiagnosticArray
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.node import Node
        from rclpy.qos import QoSProfile, ReliabilityPolicy
        from rosgraph_msgs.msg import Clock

        from shiproute_msgs.msg import ShipState

        self.node = Node("replay_test_peer", context=ctx)
        self.executor = SingleThreadedExecutor(context=ctx)
        self.executor.add_node(self.node)
        self.states: list[tuple[float, int]] = []  # (wall s, stamp ns)
        self.clock: list[tuple[float, int]] = []
        self.diag: list[dict[str, str]] = []
        self.node.create_subscription(ShipState, topics.SHIP_STATE, self._on_state,
                                      QoSProfile(depth=1000))
        self.node.create_subscription(
            Clock, "/clock", lambda m: self.clock.append(
                (time.monotonic(), m.clock.sec * 10**9 + m.clock.nanosec)),
            QoSProfile(depth=10, reliability=ReliabilityPolicy.BEST_EFFORT))
        self.node.create_subscription(
            DiagnosticArray, "/diagnostics",
            lambda m: self.diag.append({kv.key: kv.value for kv in m.status[0].values}), 10)

    def _on_state(self, m: Any) -> None:
        self.states.append((time.monotonic(), m.header.stamp.sec * 10**9 + m.header.stamp.nanosec))

    def until(self, pred: Any, timeout_s: float, what: str) -> Any:
        return rosproc.spin_until(self.executor, pred, timeout_s, what)

    def call(self, srv_type: Any, name: str, request: Any) -> Any:
        client = self.node.create_client(srv_type, name)
        self.until(client.service_is_ready, 20, f"service {name}")
        future = client.call_async(request)
        self.until(future.done, 10, f"response of {name}")
        return future.result()

    def pause(self, paused: bool) -> Any:
        from std_srvs.srv import SetBool

        return self.call(SetBool, "/shiproute_replay/pause", SetBool.Request(data=paused))

    def spin_for(self, seconds: float) -> None:
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            self.executor.spin_once(timeout_sec=0.02)


def _replay(bag: Path, dom: int, *params: str) -> rosproc.RosProcess:
    args = ["--ros-args", "-p", f"bag:={bag}", "-p", f"rate:={RATE}", "-p", "start_paused:=true"]
    for p in params:
        args += ["-p", p]
    return rosproc.RosProcess.script("shiproute_replay_node", *args, domain_id=dom,
                                     name="replay")


def test_timing_clock_and_diagnostics_at_100x(tmp_path: Path):
    # irregular recording: 1 s and 3 s intervals -> 10 ms and 30 ms at 100x
    offsets = list(itertools.accumulate([0.0] + [1.0, 3.0] * 60))
    bag = _write_bag(tmp_path / "timing", offsets)
    dom = rosproc.random_domain_id()
    with _replay(bag, dom), rosproc.ros_context(dom) as ctx:
        peer = Peer(ctx)
        peer.until(lambda: peer.node.count_publishers(topics.SHIP_STATE) > 0, 20,
                   "replay publisher")
        assert peer.pause(False).success
        peer.until(lambda: len(peer.states) == len(offsets), 30, "all states")
        peer.until(lambda: any(d.get("finished") == "True" for d in peer.diag), 10, "finish")
    wall = np.array([w for w, _ in peer.states])
    stamps = np.array([s for _, s in peer.states])
    assert (stamps == T0_NS + (np.array(offsets) * 1e9).astype(np.int64)).all()
    expected = np.diff(stamps) / 1e9 / RATE
    got = np.diff(wall)
    assert np.median(np.abs(got - expected)) < 0.003
    assert np.percentile(np.abs(got - expected), 90) < 0.015
    assert wall[-1] - wall[0] == pytest.approx(offsets[-1] / RATE, rel=0.05)
    # /clock advances with the bag at the replay rate and never runs back
    clock = np.array(peer.clock, dtype=float)
    assert len(clock) > 20 and np.all(np.diff(clock[:, 1]) >= 0)
    assert clock[0, 1] >= T0_NS and clock[-1, 1] <= stamps[-1]
    slope = (clock[-1, 1] - clock[0, 1]) / 1e9 / (clock[-1, 0] - clock[0, 0])
    assert slope == pytest.approx(RATE, rel=0.1)
    final = next(d for d in peer.diag if d.get("finished") == "True")
    assert final["messages_read"] == str(len(offsets)) and final["messages_skipped"] == "0"


def test_pause_resume_and_seek(tmp_path: Path):
    from shiproute_msgs.srv import Seek

    bag = _write_bag(tmp_path / "long", [float(i) for i in range(3000)])  # 30 s at 100x
    dom = rosproc.random_domain_id()
    with _replay(bag, dom), rosproc.ros_context(dom) as ctx:
        peer = Peer(ctx)
        peer.until(lambda: peer.node.count_publishers(topics.SHIP_STATE) > 0, 20,
                   "replay publisher")
        peer.spin_for(0.5)
        assert peer.states == []  # start_paused holds everything
        peer.pause(False)
        peer.until(lambda: len(peer.states) >= 50, 10, "first states")
        peer.pause(True)
        peer.spin_for(0.3)  # let in-flight messages arrive
        held = len(peer.states)
        peer.spin_for(1.0)  # 100 messages would arrive in 1 s if not paused
        assert len(peer.states) == held
        res = peer.call(Seek, "/shiproute_replay/seek", Seek.Request(offset_s=2000.0))
        assert res.success, res.message
        peer.pause(False)
        peer.until(lambda: peer.states[-1][1] >= T0_NS + 2050 * 10**9, 10, "after seek")
        after = [s for _, s in peer.states[held:]]
        assert min(after) >= T0_NS + 2000 * 10**9  # nothing from before the seek target
        assert after[0] <= T0_NS + 2001 * 10**9
        res = peer.call(Seek, "/shiproute_replay/seek", Seek.Request(offset_s=-5.0))
        assert not res.success and "offset" in res.message


if __name__ == "__main__":
    sys.exit(pytest.main([__file__, "-v"]))
