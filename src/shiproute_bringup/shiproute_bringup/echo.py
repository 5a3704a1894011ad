"""Print live messages of a topic (type discovered from the graph unless --type is given)."""

from __future__ import annotations

import argparse
import sys
import time

import yaml

from shiproute_bringup.errors import EchoError
from shiproute_bringup.msgdict import message_class, to_plain
from shiproute_core import topics


def _yaml_dump(data: object) -> str:
    return yaml.safe_dump(data, sort_keys=False, default_flow_style=None, width=100)


def main(argv: list[str]) -> int:
    """``shiproute echo <topic> [--type pkg/msg/Type] [--count N] [--timeout S]``."""
    parser = argparse.ArgumentParser(prog="shiproute echo", description=__doc__)
    parser.add_argument("topic", help=f"topic name, e.g. {topics.PLAN_ROUTE}")
    parser.add_argument("--type", dest="type_name", default=None,
                        help="message type pkg/msg/Type (default: from the publishers)")
    parser.add_argument("--count", type=int, default=0, help="exit after N messages (0 = run)")
    parser.add_argument("--timeout", type=float, default=None, metavar="S",
                        help="give up after S seconds (exit 1 if fewer than --count arrived)")
    parser.add_argument("--full", action="store_true", help="print whole arrays (default: 16)")
    args = parser.parse_args(argv)

    import rclpy
    from rclpy.node import Node
    from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy

    topic = args.topic if args.topic.startswith("/") else "/" + args.topic
    rclpy.init()
    node = Node("shiproute_echo", start_parameter_services=False)
    deadline = None if args.timeout is None else time.monotonic() + args.timeout
    received = 0
    try:
        type_name = args.type_name or _discover_type(node, topic, deadline, rclpy)
        if type_name is None:
            print(f"shiproute echo: no publisher of {topic} found"
                  + (f" within {args.timeout:g} s" if args.timeout else ""), file=sys.stderr)
            return 1
        cls = message_class(type_name)
        infos = node.get_publishers_info_by_topic(topic)
        latched = bool(infos) and all(i.qos_profile.durability == DurabilityPolicy.TRANSIENT_LOCAL
                                      for i in infos)
        best_effort = bool(infos) and all(
            i.qos_profile.reliability == ReliabilityPolicy.BEST_EFFORT for i in infos)
        qos = QoSProfile(depth=10,
                         durability=DurabilityPolicy.TRANSIENT_LOCAL if latched
                         else DurabilityPolicy.VOLATILE,
                         reliability=ReliabilityPolicy.BEST_EFFORT if best_effort
                         else ReliabilityPolicy.RELIABLE)
        max_array = None if args.full else 16

        def on_msg(msg: object) -> None:
            nonlocal received
            received += 1
            sys.stdout.write(_yaml_dump(to_plain(msg, max_array)) + "---\n")
            sys.stdout.flush()

        node.create_subscription(cls, topic, on_msg, qos)
        while rclpy.ok() and (args.count <= 0 or received < args.count):
            if deadline is not None and time.monotonic() >= deadline:
                break
            rclpy.spin_once(node, timeout_sec=0.1)
    except EchoError as exc:
        print(f"shiproute echo: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        return 0
    finally:
        node.destroy_node()
        rclpy.try_shutdown()
    if args.count > 0 and received < args.count:
        print(f"shiproute echo: {received} of {args.count} messages on {topic} before timeout",
              file=sys.stderr)
        return 1
    return 0


def _discover_type(node: object, topic: str, deadline: float | None, rclpy: object) -> str | None:
    """Wait for the topic in the graph and return its (first) type name."""
    while deadline is None or time.monotonic() < deadline:
        for name, types in node.get_topic_names_and_types():  # type: ignore[attr-defined]
            if name == topic and types:
                return str(types[0])
        rclpy.spin_once(node, timeout_sec=0.1)  # type: ignore[attr-defined]
    return None
