"""What the cross-process node benches share: starting the weather and planner nodes, the
in-process ROS peer that plays ship and integrator, and the nodes' memory readings."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import psutil

from shiproute_bringup.rosproc import RosProcess, console_script


def start_nodes(domain_id: int, weather_params: Sequence[str], rta: str, budget_s: float,
                planner_params: Sequence[str] = ()) -> tuple[RosProcess, RosProcess]:
    """The weather and planner nodes as separate processes: `*_params` are `name:=value`."""
    def ros_args(params: Sequence[str]) -> list[str]:
        return ["--ros-args", *(arg for p in params for arg in ("-p", p))]

    weather = RosProcess([console_script("shiproute_weather_node"), *ros_args(weather_params)],
                         domain_id=domain_id, name="weather")
    planner = RosProcess([console_script("shiproute_planner_node"), *ros_args(
        [f"rta:={rta}", f"budget_s:={budget_s}", *planner_params])],
        domain_id=domain_id, name="planner")
    return weather, planner


class BenchPeer:
    """An rclpy context, node and single-threaded executor of the bench process itself."""

    def __init__(self, name: str, domain_id: int) -> None:
        import rclpy
        from rclpy.context import Context
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy

        self.context = Context()
        rclpy.init(context=self.context, domain_id=domain_id)
        self.node = rclpy.create_node(name, context=self.context)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)
        #: reliable, transient-local, depth 1: what the nodes use for cycles and plans
        self.latched: Any = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE,
                                       durability=DurabilityPolicy.TRANSIENT_LOCAL)

    def spin_once(self, timeout_s: float) -> None:
        """Run at most one ready callback."""
        self.executor.spin_once(timeout_sec=timeout_s)

    def close(self) -> None:
        """Shut executor, node and context down."""
        self.executor.shutdown()
        self.node.destroy_node()
        self.context.try_shutdown()


def rss_mb(pid: int) -> float:
    """Resident memory of a process now [MiB]; NaN when it is gone."""
    try:
        return float(psutil.Process(pid).memory_info().rss) / 2**20
    except psutil.Error:
        return math.nan


def peak_rss_mb(pid: int) -> float:
    """Highest resident memory of a process so far (Linux VmHWM) [MiB]; NaN elsewhere."""
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024
    except OSError:
        pass
    return math.nan
