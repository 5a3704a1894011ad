"""``shiproute bag record``: record live topics (raw CDR) into a rosbag2 MCAP bag.

Generic subscriptions with ``raw=True`` hand over the serialized bytes, which are written
unchanged with the type's message definition embedded (from the rosbags typestore, extended
by installed ``share/<pkg>/msg/*.msg`` files) so Foxglove and rosbags open the bag.
Stops on SIGINT/SIGTERM or after ``--duration`` and always closes the bag properly.
"""

from __future__ import annotations

import argparse
import signal
import sys
import time
from pathlib import Path

import rclpy
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from rosbags.typesys.store import Typestore

from ..bag.bagwriter import BagWriter, qos_yaml
from ..bag.typestore import build_typestore, register_schema
from ..errors import MessageTypeError
from .convert import rclpy_class


def ensure_type(store: Typestore, typename: str) -> bool:
    """Make ``typename`` known to ``store`` from the installed .msg file; False if impossible."""
    if typename in store.fielddefs:
        return True
    pkg, _, name = typename.partition("/msg/")
    path = Path(sys.prefix) / "share" / pkg / "msg" / f"{name}.msg"
    return path.is_file() and register_schema(store, typename, path.read_text(encoding="utf-8"))


class Recorder(Node):
    """Subscribes to the requested (or all) topics and writes every message to a BagWriter."""

    def __init__(self, writer: BagWriter, topics: list[str]) -> None:
        super().__init__("shiproute_bag_record")
        self.writer = writer
        self.wanted = set(topics)
        self.subs: dict[str, object] = {}
        self.skipped_types: set[str] = set()

    def discover(self) -> None:
        """Subscribe to matching topics that appeared since the last call."""
        for topic, types in self.get_topic_names_and_types():
            if topic in self.subs or (self.wanted and topic not in self.wanted):
                continue
            if self.wanted == set() and topic in ("/rosout", "/parameter_events"):
                continue
            if not self.get_publishers_info_by_topic(topic):
                continue  # subscriber-only so far: wait for a publisher to know its QoS
            typename = types[0]
            try:
                cls = rclpy_class(typename)
                if not ensure_type(self.writer.store, typename):
                    raise MessageTypeError(f"no definition for {typename}")
            except (ImportError, AttributeError, MessageTypeError) as exc:
                if typename not in self.skipped_types:
                    self.get_logger().warning(f"not recording {topic}: {exc}")
                    self.skipped_types.add(typename)
                continue
            qos = self._qos(topic)
            self.writer.add_topic(topic, typename, self._qos_yaml(qos))
            self.subs[topic] = self.create_subscription(
                cls, topic, lambda data, t=topic: self._on_msg(t, data), qos, raw=True)
            self.get_logger().info(f"recording {topic} [{typename}]")

    def _qos(self, topic: str) -> QoSProfile:
        qos = QoSProfile(depth=1000, reliability=ReliabilityPolicy.RELIABLE)
        infos = self.get_publishers_info_by_topic(topic)
        if infos and all(i.qos_profile.durability == DurabilityPolicy.TRANSIENT_LOCAL
                         for i in infos):
            qos.durability = DurabilityPolicy.TRANSIENT_LOCAL
        if infos and any(i.qos_profile.reliability == ReliabilityPolicy.BEST_EFFORT
                         for i in infos):
            qos.reliability = ReliabilityPolicy.BEST_EFFORT
        return qos

    @staticmethod
    def _qos_yaml(qos: QoSProfile) -> str:
        return qos_yaml(qos.reliability.name.lower(), qos.durability.name.lower(), qos.depth)

    def _on_msg(self, topic: str, data: bytes) -> None:
        self.writer.write(topic, time.time_ns(), data)


def record_main(args: argparse.Namespace) -> int:
    """Run the recorder until a signal or the duration ends; print the counts."""
    stop = {"flag": False}

    def _stop(*_: object) -> None:
        stop["flag"] = True

    rclpy.init(args=None, signal_handler_options=rclpy.signals.SignalHandlerOptions.NO)
    signal.signal(signal.SIGINT, _stop)
    signal.signal(signal.SIGTERM, _stop)
    writer = BagWriter(args.output, build_typestore())
    node = Recorder(writer, list(args.topics))
    t_end = time.monotonic() + args.duration if args.duration > 0 else float("inf")
    next_scan = 0.0
    try:
        while not stop["flag"] and time.monotonic() < t_end:
            if time.monotonic() >= next_scan:
                node.discover()
                next_scan = time.monotonic() + args.discovery_s
            rclpy.spin_once(node, timeout_sec=0.05)
    finally:
        writer.close()
        node.destroy_node()
        rclpy.try_shutdown()
    print(f"recorded {sum(writer.counts.values())} messages to {args.output}: {writer.counts}")
    return 0
