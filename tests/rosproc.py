"""Helpers for cross-process ROS tests (re-exported from shiproute_bringup.rosproc).

    from rosproc import RosProcess, random_domain_id, wait_until
    dom = random_domain_id()
    with RosProcess.script("shiproute_weather_node", "--ros-args", "-p", "x:=1.0",
                           domain_id=dom, name="weather") as weather:
        weather.wait_for_line(r"ready", timeout_s=15)
    # on exit: SIGINT -> SIGTERM -> SIGKILL to the child's process group, each after a deadline

Tests under src/<pkg>/test/ import the same API from ``shiproute_bringup.rosproc``.
``ros_context(domain_id)`` gives an isolated rclpy context for the test process itself.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterator
from typing import Any

from shiproute_bringup.errors import ProcessTimeoutError
from shiproute_bringup.rosproc import (
    RosProcess,
    console_script,
    random_domain_id,
    ros_env,
    stop_group,
    wait_until,
)

__all__ = ["ProcessTimeoutError", "RosProcess", "console_script", "random_domain_id",
           "ros_context", "ros_env", "spin_until", "stop_group", "wait_until"]


@contextlib.contextmanager
def ros_context(domain_id: int) -> Iterator[Any]:
    """An initialised rclpy Context on ``domain_id`` with LOCALHOST discovery; shut down after."""
    import rclpy
    from rclpy.context import Context

    os.environ.setdefault("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")
    context = Context()
    rclpy.init(context=context, domain_id=domain_id)
    try:
        yield context
    finally:
        context.try_shutdown()


def spin_until(executor: Any, predicate: Any, timeout_s: float, what: str = "condition") -> Any:
    """Spin ``executor`` in 50 ms steps until ``predicate()`` is truthy; raise after timeout_s."""

    def step() -> Any:
        value = predicate()
        if not value:
            executor.spin_once(timeout_sec=0.05)
        return value

    return wait_until(step, timeout_s, interval_s=0.0, what=what)
