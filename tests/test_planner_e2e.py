"""Planner node end to end across processes: weather node -> planner node -> subscribers.

The weather node serves the bundled calm June scenario from a watched directory; this
process plays the ship (ShipState) and an integrator (plan subscriber). Checked: a plan at
departure; a new cycle gives a new plan (new id, new cycle) within the re-plan budget that starts
at the ship's current position; Path, RpmProfile and RoutePlan agree; a late plan is flagged
infeasible with the RTA as reason (plan quality itself is tested in the planner); a corrupt file
and a half-delivered cycle do not disturb the plan; a restarted planner reloads its seed pool.
"""

from __future__ import annotations

import math
import shutil
import time
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import rosproc

pytestmark = [pytest.mark.ros, pytest.mark.slow]

RTA = "2026-06-16T18:00:00Z"
DEPART_S = 1780509600.0  # 2026-06-03T18:00:00Z (calm_june cycle 12Z + 6 h); RTA 13 days later
BUDGET_S = 1.5
BUSAN = (35.08, 129.112)


class Integrator:
    """Ship-state publisher and plan subscriber in the test process."""

    def __init__(self, ctx: Any) -> None:
        from nav_msgs.msg import Path as PathMsg
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.node import Node
        from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy

        from shiproute_msgs.msg import (
            ForecastCycle,
            ForecastSlice,
            RoutePlan,
            RpmProfile,
            ShipState,
        )

        self.node = Node("planner_test_integrator", context=ctx)
        self.executor = SingleThreadedExecutor(context=ctx)
        self.executor.add_node(self.node)
        latched = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE,
                             durability=DurabilityPolicy.TRANSIENT_LOCAL)
        self.plans: list[Any] = []
        self.paths: dict[str, Any] = {}
        self.profiles: dict[str, Any] = {}
        self._last_path = None
        self.node.create_subscription(RoutePlan, "/shiproute/plan/route", self.plans.append,
                                      latched)
        self.node.create_subscription(PathMsg, "/shiproute/plan/path",
                                      lambda m: setattr(self, "_last_path", m), latched)
        self.node.create_subscription(
            RpmProfile, "/shiproute/plan/rpm_profile",
            lambda m: self.profiles.__setitem__(m.plan_id, m), latched)
        self.state_pub = self.node.create_publisher(ShipState, "/shiproute/ship_state", 10)
        self.cycle_pub = self.node.create_publisher(ForecastCycle, "/shiproute/forecast/cycle",
                                                    latched)
        slices_qos = QoSProfile(depth=512, reliability=ReliabilityPolicy.RELIABLE,
                                durability=DurabilityPolicy.TRANSIENT_LOCAL)
        self.slice_pub = self.node.create_publisher(ForecastSlice, "/shiproute/forecast/slices",
                                                    slices_qos)
        self.ship_state_type = ShipState

    def send_state(self, lat: float, lon: float, t_s: float) -> None:
        msg = self.ship_state_type()
        msg.header.stamp.sec = int(t_s)
        msg.header.stamp.nanosec = int((t_s % 1) * 1e9)
        msg.latitude_deg, msg.longitude_deg = lat, lon
        msg.sog_kn, msg.cog_deg, msg.heading_deg = 17.0, 60.0, 60.0
        self.state_pub.publish(msg)

    def spin_until(self, predicate: Any, timeout_s: float, what: str,
                   state: tuple[float, float, float] | None = None) -> Any:
        deadline = time.monotonic() + timeout_s
        next_state = 0.0
        while time.monotonic() < deadline:
            if state is not None and time.monotonic() >= next_state:
                self.send_state(*state)
                next_state = time.monotonic() + 0.5
            self.executor.spin_once(timeout_sec=0.05)
            if self._last_path is not None and self.plans:
                self.paths[self.plans[-1].plan_id] = self._last_path
            value = predicate()
            if value:
                return value
        raise AssertionError(f"{what} not within {timeout_s:.0f} s")

    def close(self) -> None:
        self.executor.shutdown()
        self.node.destroy_node()


def _planner(dom: int, pool: Path, out: Path) -> rosproc.RosProcess:
    return rosproc.RosProcess.script(
        "shiproute_planner_node", "--ros-args",
        "-p", "origin:=Busan", "-p", "destination:=Long Beach", "-p", f"rta:={RTA}",
        "-p", "ship:=container_4600teu", "-p", f"budget_s:={BUDGET_S}",
        "-p", f"seed_pool_dir:={pool}", "-p", f"output_dir:={out}", "-p", "write_png:=false",
        domain_id=dom, name="planner")


def _weather(dom: int, watch: Path) -> rosproc.RosProcess:
    return rosproc.RosProcess.script(
        "shiproute_weather_node", "--ros-args", "-p", f"watch_dir:={watch}",
        "-p", "watch_period_s:=0.3", "-p", "settle_s:=0.3", domain_id=dom, name="weather")


def _check_consistent(plan: Any, path: Any, profile: Any) -> None:
    from shiproute_planner.path_frame import ecef_to_lat_lon

    n = len(plan.waypoints)
    assert len(path.poses) == n and len(profile.stages) == n - 1
    assert path.header.frame_id == "earth"
    x = np.array([p.pose.position.x for p in path.poses])
    y = np.array([p.pose.position.y for p in path.poses])
    z = np.array([p.pose.position.z for p in path.poses])
    lat, lon = ecef_to_lat_lon(x, y, z)
    assert np.allclose(lat, [w.latitude_deg for w in plan.waypoints], atol=1e-9)
    d_lon = lon - np.array([w.longitude_deg for w in plan.waypoints])
    assert np.allclose((d_lon + 180.0) % 360.0 - 180.0, 0.0, atol=1e-9)
    for w, s, pose in zip(plan.waypoints[:-1], profile.stages, path.poses[:-1], strict=True):
        assert s.shaft_rpm == w.shaft_rpm and s.heading_deg == w.heading_deg
        assert (s.start_time.sec, s.start_time.nanosec) == (w.time.sec, w.time.nanosec)
        assert (pose.header.stamp.sec, pose.header.stamp.nanosec) == (w.time.sec, w.time.nanosec)
    fuel = sum(w.leg_fuel_t for w in plan.waypoints[:-1])
    assert math.isclose(fuel, plan.total_fuel_t, rel_tol=1e-9)
    _check_flagged(plan)


def _check_flagged(plan: Any) -> None:
    """A plan is feasible exactly when it has no reasons, and a late one says so."""
    assert plan.feasible == (len(plan.infeasible_reasons) == 0)
    if plan.eta.sec > plan.rta.sec:
        assert not plan.feasible
        assert any("RTA" in r for r in plan.infeasible_reasons), list(plan.infeasible_reasons)


def test_plan_replan_on_new_cycle_corrupt_file_half_cycle_and_restart(tmp_path: Path) -> None:
    from shiproute_weather.ros.convert import dataset_to_msgs
    from shiproute_weather.scenarios.catalogue import scenario_dataset, scenario_path

    watch, pool, out = tmp_path / "watch", tmp_path / "pool", tmp_path / "plans"
    watch.mkdir()
    shutil.copy(scenario_path("calm_june"), watch / "calm_june.nc")
    dom = rosproc.random_domain_id()
    with rosproc.ros_context(dom) as ctx, _weather(dom, watch) as weather:
        peer = Integrator(ctx)
        planner = _planner(dom, pool, out)
        try:
            # 1. Departure: the ship at Busan -> a plan on the first cycle.
            at_busan = (BUSAN[0], BUSAN[1], DEPART_S)
            peer.spin_until(lambda: peer.plans, 90, "first plan", state=at_busan)
            first = peer.plans[-1]
            peer.spin_until(lambda: first.plan_id in peer.profiles and
                            first.plan_id in peer.paths, 10, "path + profile of the first plan")
            _check_consistent(first, peer.paths[first.plan_id], peer.profiles[first.plan_id])
            assert abs(first.waypoints[0].latitude_deg - BUSAN[0]) < 0.3
            # Files are written after publishing, off the executor thread.
            rosproc.wait_until(lambda: out.is_dir() and any(out.glob(f"*{first.plan_id}.rtz")),
                               20.0)

            # 2. A corrupt file in the watched directory: no new plan, weather keeps serving.
            (watch / "broken.nc").write_bytes(b"CDF\x01" + b"\x00garbage" * 100)
            weather.wait_for_line(r"broken\.nc", timeout_s=20)
            n_before = len(peer.plans)
            peer.spin_until(lambda: True, 0.1, "spin")
            t_end = time.monotonic() + 3.0
            while time.monotonic() < t_end:
                peer.executor.spin_once(timeout_sec=0.1)
            assert len(peer.plans) == n_before

            # 3. Half a cycle from an integrator: announced, one slice missing -> no plan.
            ds = scenario_dataset("calm_june").isel(time=slice(1, 129))
            ds.attrs["cycle_id"] = "half-test-cycle"
            cycle, slices = dataset_to_msgs(ds)
            peer.cycle_pub.publish(cycle)
            for s in slices[:-1]:
                peer.slice_pub.publish(s)
            t_end = time.monotonic() + 4.0
            while time.monotonic() < t_end:
                peer.executor.spin_once(timeout_sec=0.1)
            assert all(p.cycle_id != "half-test-cycle" for p in peer.plans)

            # 4. The missing slice completes it -> re-plan from the ship's current position.
            t_now = DEPART_S + 12 * 3600.0
            under_way = (36.9, 133.0, t_now)
            peer.send_state(*under_way)
            peer.spin_until(lambda: True, 0.5, "state", state=under_way)
            start = time.monotonic()
            peer.slice_pub.publish(slices[-1])
            second = peer.spin_until(
                lambda: next((p for p in peer.plans if p.cycle_id == "half-test-cycle"), None),
                BUDGET_S + 30, "re-plan on the completed cycle", state=under_way)
            latency = time.monotonic() - start
            assert second.plan_id != first.plan_id
            assert latency < BUDGET_S + 30
            w0 = second.waypoints[0]
            assert abs(w0.latitude_deg - under_way[0]) < 1e-6
            assert abs(w0.longitude_deg - under_way[1]) < 1e-6
            assert abs(w0.time.sec - t_now) < 1.0
            _check_flagged(second)

            # 5. Restart: the planner reloads its seed pool and plans again.
            planner.stop()
            planner = _planner(dom, pool, out)
            planner.wait_for_line(r"seed pool: [1-9]\d* seed", timeout_s=60)
            n_before = len(peer.plans)
            peer.spin_until(lambda: len(peer.plans) > n_before, 90, "plan after restart",
                            state=under_way)
        finally:
            planner.stop()
            peer.close()
