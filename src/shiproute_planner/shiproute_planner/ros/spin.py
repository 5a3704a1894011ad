"""Spinning the planner node: a multi-threaded executor for the node and a single-threaded one
for its forecast intake node, so slices are packed in arrival order on one thread."""

from __future__ import annotations

import threading
from typing import Any

from rclpy.executors import MultiThreadedExecutor, SingleThreadedExecutor
from shiproute_core.spin import spin_quietly, spin_until_shutdown


def spin_with_intake(node: Any, intake_node: Any, num_threads: int = 4) -> None:
    """Spin `node` (and `intake_node` on a thread of its own) until shutdown, then call
    `node.shutdown()`, destroy both nodes and shut rclpy down."""
    executor = MultiThreadedExecutor(num_threads=num_threads)
    executor.add_node(node)
    intake = SingleThreadedExecutor()
    intake.add_node(intake_node)
    threading.Thread(target=spin_quietly, args=(intake,), name="forecast intake",
                     daemon=True).start()
    spin_until_shutdown(executor, (intake_node, node), stop=(node.shutdown, intake.shutdown))
