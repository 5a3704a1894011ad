"""Start-up shared by the cross-process planner tests: the weather node serving a bundled
scenario and the planner node planning Busan -> Long Beach from it, on a fresh ROS domain."""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import rosproc


@contextlib.contextmanager
def weather_and_planner(work: Path, rta: str, budget_s: float, scenario: str = "calm_june"
                        ) -> Iterator[tuple[Any, rosproc.RosProcess, rosproc.RosProcess, Path]]:
    """(rclpy context of this process, weather node, planner node, forecast file) on a random
    domain; the forecast is a link to the scenario's file in `work`, so a test may reload it.
    Both nodes are stopped (SIGINT, then harder) on exit."""
    from shiproute_weather.scenarios.catalogue import scenario_path

    forecast = work / f"{scenario}.nc"
    forecast.symlink_to(scenario_path(scenario))
    dom = rosproc.random_domain_id()
    with rosproc.ros_context(dom) as ctx, rosproc.RosProcess.script(
            "shiproute_weather_node", "--ros-args", "-p", f"forecast_files:=['{forecast}']",
            domain_id=dom, name="weather") as weather, rosproc.RosProcess.script(
            "shiproute_planner_node", "--ros-args", "-p", "origin:=Busan",
            "-p", "destination:=Long Beach", "-p", f"rta:={rta}", "-p", f"budget_s:={budget_s}",
            "-p", "write_png:=false", domain_id=dom, name="planner") as planner:
        yield ctx, weather, planner, forecast
