"""Voyage-replay node: plays a rosbag2 MCAP bag with original timing scaled by a rate.

Publishes ShipState on the ship-state topic (shiproute_core.topics.SHIP_STATE; from the bag's
ShipState or converted from NavSatFix), passes other topics through on request, publishes
/clock for use_sim_time and progress/counts on /diagnostics; services ~/pause
(std_srvs/SetBool) and ~/seek (Seek).
"""

from __future__ import annotations

import sys
import threading
import time
from typing import Any

import rclpy
from diagnostic_msgs.msg import DiagnosticArray
from rclpy._rclpy_pybind11 import RCLError
from rclpy.duration import Duration
from rclpy.executors import ExternalShutdownException, SingleThreadedExecutor
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy
from rosgraph_msgs.msg import Clock
from std_srvs.srv import SetBool

from shiproute_core import topics
from shiproute_msgs.msg import ShipState
from shiproute_msgs.srv import Seek

from ..errors import AisReplayError
from ..replay.engine import ReplayConfig, ReplayEngine, ReplayEvent
from .convert import clock_msg, diagnostic_array, rclpy_class, ship_state_to_rclpy, to_rclpy

CLOCK_QOS = QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT)
PUBLISH_ATTEMPTS = 5
ACK_WAIT_S = 10.0


def _state_qos(depth: int) -> QoSProfile:
    """Reliable ShipState QoS; depth <= 0 = keep all (the publisher then waits for slow
    reliable subscribers instead of overwriting what they have not acknowledged)."""
    if depth <= 0:
        return QoSProfile(history=HistoryPolicy.KEEP_ALL, depth=1,
                          reliability=ReliabilityPolicy.RELIABLE)
    return QoSProfile(depth=depth, reliability=ReliabilityPolicy.RELIABLE)


def _parse_remap(items: list[str]) -> dict[str, str]:
    out = {}
    for item in items:
        src, sep, dst = item.partition(":=")
        if sep and src and dst:
            out[src] = dst
    return out


class ReplayNode(Node):
    """Owns a ReplayEngine running in a worker thread; the executor serves services/timers."""

    def __init__(self) -> None:
        super().__init__("shiproute_replay")
        p = self.declare_parameter
        self.bag: str = p("bag", "").value
        self.serialized = bool(p("publish_serialized", True).value)
        self.publish_clock = bool(p("publish_clock", True).value)
        self.clock_period_s = float(p("clock_period_s", 0.01).value)
        self.exit_at_end = bool(p("exit_at_end", False).value)
        depth = int(p("qos_depth", 1000).value)
        config = ReplayConfig(
            rate=float(p("rate", 1.0).value),
            start_offset_s=float(p("start_offset_s", 0.0).value),
            loop=bool(p("loop", False).value),
            pass_topics=tuple(p("pass_topics", [""]).value or ()),
            remap=_parse_remap(list(p("remap", [""]).value or ())),
            ship_state_topic=str(p("ship_state_topic", "").value),
            max_gap_wall_s=float(p("max_gap_wall_s", 5.0).value),
        )
        start_paused = bool(p("start_paused", False).value)
        diag_period_s = float(p("diagnostics_period_s", 1.0).value)
        self.engine = ReplayEngine(self.bag, config)
        if start_paused:
            self.engine.pause()
        self.state_pub = self.create_publisher(
            ShipState, topics.SHIP_STATE,
            _state_qos(depth))
        self.clock_pub = self.create_publisher(Clock, "/clock", CLOCK_QOS)
        self.diag_pub = self.create_publisher(DiagnosticArray, topics.DIAGNOSTICS, 10)
        self.pass_pubs: dict[str, Any] = {}
        self.unpublishable: dict[str, int] = {}
        self.errors = 0
        self.publish_retries = 0
        self._last_clock_wall = 0.0
        self.create_service(SetBool, "~/pause", self._on_pause)
        self.create_service(Seek, "~/seek", self._on_seek)
        self.create_timer(diag_period_s, self._publish_diagnostics)
        self.worker = threading.Thread(target=self._run, name="replay", daemon=True)
        self.worker.start()

    # ------------------------------------------------------------------ replay thread
    def _run(self) -> None:
        try:
            self.engine.run(self._on_emit, self._on_clock)
        except AisReplayError as exc:
            self.get_logger().error(f"replay of {self.bag} stopped: {exc}")
            self.errors += 1
        if self.context.ok():
            self._publish_diagnostics()
            self.get_logger().info(f"replay finished: {self.engine.status()['published']}")

    def _on_clock(self, bag_ns: int) -> None:
        if not self.publish_clock:
            return
        now = time.monotonic()
        if now - self._last_clock_wall >= self.clock_period_s:
            self._last_clock_wall = now
            try:
                self.clock_pub.publish(clock_msg(bag_ns))
            except Exception:  # context shut down (Ctrl-C) while the worker runs
                if not self.context.ok():
                    self.engine.stop()
                    return
                raise

    def _on_emit(self, ev: ReplayEvent) -> None:
        try:
            if ev.kind == "ship_state_converted":
                assert ev.record is not None
                self.state_pub.publish(ship_state_to_rclpy(ev.record))
                return
            pub = self.state_pub if ev.kind == "ship_state" else self._pass_pub(ev)
            if pub is None:
                return
            if self.serialized:
                self._publish(pub, bytes(ev.data or b""))
            else:
                self._publish(pub, to_rclpy(self.engine.deserialize(ev), pub.msg_type))
        except Exception as exc:  # a bad message must not stop the replay
            if not self.context.ok():  # shutting down: end the replay quietly
                self.engine.stop()
                return
            self.errors += 1
            if self.errors <= 5:
                self.get_logger().warning(f"cannot publish {ev.typename} on {ev.topic}: {exc}")

    def _publish(self, pub: Any, msg: Any) -> None:
        """Publish, retrying a few times when a keep-all reliable history is full (the
        middleware times out while a slow subscriber catches up)."""
        for attempt in range(PUBLISH_ATTEMPTS):
            try:
                pub.publish(msg)
                return
            except RCLError:
                if attempt == PUBLISH_ATTEMPTS - 1 or not self.context.ok():
                    raise
                self.publish_retries += 1

    def _pass_pub(self, ev: ReplayEvent) -> Any:
        if ev.topic in self.pass_pubs:
            return self.pass_pubs[ev.topic]
        try:
            cls = rclpy_class(ev.typename)
        except (ImportError, AttributeError):
            self.unpublishable[ev.typename] = self.unpublishable.get(ev.typename, 0) + 1
            return None
        qos = QoSProfile(depth=100, reliability=ReliabilityPolicy.RELIABLE)
        meta = next((c.metadata for c in self.engine.reader.channels()
                     if self.engine.config.remap.get(c.topic, c.topic) == ev.topic), {})
        if "transient_local" in meta.get("offered_qos_profiles", ""):
            qos.durability = DurabilityPolicy.TRANSIENT_LOCAL
        self.pass_pubs[ev.topic] = self.create_publisher(cls, ev.topic, qos)
        return self.pass_pubs[ev.topic]

    # ------------------------------------------------------------------ services
    def _on_pause(self, req: SetBool.Request, resp: SetBool.Response) -> SetBool.Response:
        (self.engine.pause if req.data else self.engine.resume)()
        resp.success = True
        resp.message = "paused" if req.data else "resumed"
        return resp

    def _on_seek(self, req: Seek.Request, resp: Seek.Response) -> Seek.Response:
        problem = self.engine.seek(req.offset_s)
        resp.success = not problem
        resp.message = problem or f"seeking to {req.offset_s:.3f} s"
        return resp

    def _publish_diagnostics(self) -> None:
        st = self.engine.status()
        st["unpublishable_types"] = dict(self.unpublishable)
        st["publish_errors"] = self.errors
        st["publish_retries"] = self.publish_retries
        bad = st["messages_skipped"] or st["unknown_types"] or st["truncated"] or self.errors
        level = 1 if bad else 0
        text = (f"{100 * st['progress']:.1f}% at {st['rate']}x"
                f"{' paused' if st['paused'] else ''}{' finished' if st['finished'] else ''}")
        self.diag_pub.publish(diagnostic_array(
            self.get_clock().now().nanoseconds, "shiproute_replay", st, level, text))


def main(argv: list[str] | None = None) -> int:
    """Console script ``shiproute_replay_node``: run until Ctrl-C (or bag end with exit_at_end)."""
    rclpy.init(args=argv if argv is not None else sys.argv)
    try:
        node = ReplayNode()
    except AisReplayError as exc:
        print(f"shiproute_replay_node: {exc}", file=sys.stderr)
        rclpy.try_shutdown()
        return 2
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    try:
        while rclpy.ok():
            executor.spin_once(timeout_sec=0.2)
            if node.exit_at_end and not node.worker.is_alive():
                break
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        node.engine.stop()
        node.worker.join(timeout=2.0)
        if rclpy.ok():  # hand queued messages to reliable subscribers before leaving
            node.state_pub.wait_for_all_acked(Duration(seconds=ACK_WAIT_S))
        node.destroy_node()
        rclpy.try_shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
