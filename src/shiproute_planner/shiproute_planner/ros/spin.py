"""Spinning the planner node: a multi-threaded executor for the node and a single-threaded one
for its forecast intake node, so slices are packed in arrival order on one thread."""

from __future__ import annotations

import contextlib
import threading
from typing import Any

import rclpy
from rclpy.executors import (
    ExternalShutdownException,
    MultiThreadedExecutor,
    SingleThreadedExecutor,
)


def _spin_quietly(executor: SingleThreadedExecutor) -> None:
    """Spin until the context shuts down (Ctrl-C and SIGTERM end the main executor)."""
    with contextlib.suppress(KeyboardInterrupt, ExternalShutdownException):
        executor.spin()


def spin_with_intake(node: Any, intake_node: Any, num_threads: int = 4) -> None:
    """Spin `node` (and `intake_node` on a thread of its own) until shutdown, then call
    `node.shutdown()`, destroy both nodes and shut rclpy down."""
    executor = MultiThreadedExecutor(num_threads=num_threads)
    executor.add_node(node)
    intake = SingleThreadedExecutor()
    intake.add_node(intake_node)
    threading.Thread(target=_spin_quietly, args=(intake,), name="forecast intake",
                     daemon=True).start()
    try:
        executor.spin()
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        node.shutdown()
        intake.shutdown()
        executor.shutdown()
        intake_node.destroy_node()
        node.destroy_node()
        if rclpy.ok():
            rclpy.try_shutdown()
