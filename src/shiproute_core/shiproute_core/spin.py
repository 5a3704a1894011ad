"""How every shiproute node ends: spin until Ctrl-C or SIGTERM, then stop, destroy, shut down.

ROS-only: imported by the packages' `ros/` rooms (rclpy must be installed); the rest of
`shiproute_core` never imports it, so the core stays importable without rclpy.
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Sequence
from typing import Any

import rclpy
from rclpy.executors import ExternalShutdownException


def spin_until_shutdown(executor: Any, nodes: Sequence[Any],
                        stop: Sequence[Callable[[], object]] = ()) -> None:
    """Spin `executor` until the context shuts down (Ctrl-C and SIGTERM end it quietly); then
    call each of `stop` (worker threads, other executors), shut the executor down, destroy
    `nodes` in order and shut rclpy down."""
    try:
        executor.spin()
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        for step in stop:
            step()
        executor.shutdown()
        for node in nodes:
            node.destroy_node()
        rclpy.try_shutdown()


def spin_quietly(executor: Any) -> None:
    """Spin `executor` until the context shuts down, for a thread of its own (no clean-up)."""
    with contextlib.suppress(KeyboardInterrupt, ExternalShutdownException):
        executor.spin()
