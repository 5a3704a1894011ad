"""`shiproute_display_node`: serves the bridge display page and publishes Foxglove topics.

Thin shell: subscriptions decode messages with `convert` into the ROS-free `DisplayState`,
whose events go to the pages through the non-blocking `Feed`; the HTTP server runs on its own
threads. A bad message is counted, logged once per kind and shown on the page, never fatal.
"""

from __future__ import annotations

import math
import sys
import threading
from typing import Any

import rclpy
from rcl_interfaces.msg import ParameterDescriptor, SetParametersResult
from rclpy.clock import Clock, ClockType
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from sensor_msgs.msg import NavSatFix
from shiproute_core.spin import spin_until_shutdown
from std_msgs.msg import Float64

from foxglove_msgs.msg import GeoJSON
from shiproute_core import topics
from shiproute_msgs.msg import ForecastCycle, ForecastSlice, RoutePlan, RpmProfile, ShipState

from .. import geometry
from ..coastline import ChartBox, coastline_json
from ..errors import DisplayError, MalformedMessageError
from ..feed import Feed
from ..page_payload import stages_of
from ..server import DisplayServer, Routes, check_bind
from ..state import DisplayState
from . import convert
from .dds_profile import forget_profile, use_windowed_slice_reader

WORLD = ChartBox(-180.0, 180.0, -80.0, 80.0)

PARAMETERS: dict[str, tuple[Any, str]] = {
    "port": (8765, "TCP port of the page (0: any free port)"),
    "bind_address": ("127.0.0.1", "IP address to serve on (127.0.0.1: this machine only)"),
    "max_clients": (16, "live pages served at once"),
    "client_queue_depth": (64, "events queued per page before its backlog is dropped"),
    "push_rate_hz": (4.0, "ship updates pushed to the pages per second at most"),
    "track_max_points": (5000, "ship track points kept (~1 NM apart)"),
    "forecast_max_cells": (8000, "Hs cells per forecast slice on the page"),
    "coast_margin_deg": (6.0, "least coastline margin around plan and track [deg]"),
    "publish_foxglove": (True, "publish the GeoJSON, NavSatFix and planned-RPM topics"),
}


def check_parameter(name: str, value: Any) -> str | None:
    """Reason a parameter value is invalid, None when it is fine."""
    if name == "bind_address":
        try:
            check_bind(str(value), 0)
        except DisplayError as exc:
            return str(exc)
    elif name == "port" and not (isinstance(value, int) and 0 <= value <= 65535):
        return f"port {value!r} is not in 0..65535"
    elif name in ("max_clients", "client_queue_depth", "track_max_points",
                  "forecast_max_cells") and not (isinstance(value, int) and value >= 1):
        return f"{name} {value!r} must be an integer >= 1"
    elif name in ("push_rate_hz", "coast_margin_deg") and not (
            isinstance(value, int | float) and math.isfinite(value) and value > 0):
        return f"{name} {value!r} must be a positive number"
    return None


class DisplayNode(Node):
    """Subscriptions -> DisplayState -> pages (SSE) and Foxglove topics."""

    def __init__(self) -> None:
        super().__init__("shiproute_display")
        for name, (default, text) in PARAMETERS.items():
            self.declare_parameter(name, default, ParameterDescriptor(description=text))
        for name in PARAMETERS:
            reason = check_parameter(name, self._p(name))
            if reason:
                raise DisplayError(f"parameter {reason}")
        self.add_on_set_parameters_callback(self._on_set_parameters)
        self.state = DisplayState(track_max_points=self._p("track_max_points"))
        self.feed = Feed(self._p("max_clients"), self._p("client_queue_depth"))
        self._coast_lock = threading.Lock()
        self._coast: tuple[ChartBox, bytes] | None = None
        self._track_sent = 0
        self._ship_dirty = False
        self._geojson_dirty = False
        self._logged_problems: set[str] = set()
        self.server = DisplayServer(
            Routes(self._snapshot, self._coast_json,
                   self.state.slice_json, self.state.geojson, self._health),
            self.feed, str(self._p("bind_address")), int(self._p("port")))
        latched = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE,
                             durability=DurabilityPolicy.TRANSIENT_LOCAL)
        slices_qos = QoSProfile(depth=512, reliability=ReliabilityPolicy.RELIABLE,
                                durability=DurabilityPolicy.TRANSIENT_LOCAL)
        reliable = QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE)
        self.create_subscription(RoutePlan, topics.PLAN_ROUTE, self._on_plan, latched)
        self.create_subscription(RpmProfile, topics.PLAN_RPM_PROFILE, self._on_profile, latched)
        self.create_subscription(ShipState, topics.SHIP_STATE, self._on_ship, reliable)
        self.create_subscription(ForecastCycle, topics.FORECAST_CYCLE, self._on_cycle, latched)
        self.create_subscription(ForecastSlice, topics.FORECAST_SLICES, self._on_slice, slices_qos)
        self._fox = bool(self._p("publish_foxglove"))
        if self._fox:
            self.pub_geojson = self.create_publisher(GeoJSON, topics.DISPLAY_GEOJSON, latched)
            self.pub_ship_fix = self.create_publisher(NavSatFix, topics.DISPLAY_SHIP_FIX, reliable)
            self.pub_plan_fix = self.create_publisher(NavSatFix, topics.DISPLAY_PLAN_FIX, reliable)
            self.pub_rpm = self.create_publisher(Float64, topics.DISPLAY_PLANNED_RPM, reliable)
        # The page is for people: its timers run on the wall clock even when the node follows
        # a replay's /clock at thousands of times real time (use_sim_time).
        wall = Clock(clock_type=ClockType.STEADY_TIME)
        self.create_timer(1.0 / float(self._p("push_rate_hz")), self._push_ship, clock=wall)
        self.create_timer(1.0, self._push_stats, clock=wall)
        self.create_timer(5.0, self._publish_geojson_if_dirty, clock=wall)
        self.server.start()
        self.get_logger().info(f"bridge display on {self.server.url}")

    def _p(self, name: str) -> Any:
        return self.get_parameter(name).value

    def _on_set_parameters(self, params: list) -> SetParametersResult:
        for p in params:
            if p.name in PARAMETERS:
                reason = check_parameter(p.name, p.value)
                if reason:
                    return SetParametersResult(successful=False, reason=reason)
                if p.name in ("port", "bind_address", "max_clients", "client_queue_depth"):
                    return SetParametersResult(successful=False,
                                               reason=f"{p.name} is fixed once the page serves")
        return SetParametersResult(successful=True)

    # ------------------------------------------------------------------ inputs
    def _bad(self, topic: str, err: Exception) -> None:
        self.feed.publish(*self.state.malformed(topic, str(err)))
        key = f"{topic}:{type(err).__name__}"
        if key not in self._logged_problems:
            self._logged_problems.add(key)
            self.get_logger().warning(f"message on {topic} not shown: {err}")

    def _guard(self, topic: str, fn, msg) -> None:
        self.state.count(topic)
        try:
            fn(msg)
        except MalformedMessageError as err:
            self._bad(topic, err)
        except Exception as err:
            self._bad(topic, MalformedMessageError(f"{type(err).__name__}: {err}"))

    def _on_plan(self, msg: RoutePlan) -> None:
        self._guard(topics.PLAN_ROUTE, self._take_plan, msg)

    def _take_plan(self, msg: RoutePlan) -> None:
        plan = convert.plan_from_msg(msg)
        for name, payload in self.state.on_plan(plan):
            self.feed.publish(name, self._with_box(payload))
        self._warm_coast()
        self._publish_geojson()

    def _on_profile(self, msg: RpmProfile) -> None:
        def take(m: RpmProfile) -> None:
            for name, payload in self.state.on_profile(convert.profile_from_msg(m)):
                self.feed.publish(name, self._with_box(payload))
        self._guard(topics.PLAN_RPM_PROFILE, take, msg)

    def _on_ship(self, msg: ShipState) -> None:
        self._guard(topics.SHIP_STATE, self._take_fix, msg)

    def _take_fix(self, msg: ShipState) -> None:
        fix = convert.fix_from_msg(msg)
        self.state.on_fix(fix)
        self._ship_dirty = self._geojson_dirty = True
        if not self._fox:
            return
        self.pub_ship_fix.publish(convert.navsatfix(fix.lat_deg, fix.lon_deg, fix.time_s,
                                                    "own_ship"))
        plan, profile = self.state.current_plan()
        if plan is not None:
            lat, lon, _ = geometry.position_at(plan, fix.time_s)
            self.pub_plan_fix.publish(convert.navsatfix(lat, lon, fix.time_s, "planned"))
            stages = stages_of(plan, profile)
            i = geometry.stage_index(stages, fix.time_s)
            if i >= 0 and fix.time_s < plan.waypoints[-1].time_s:
                self.pub_rpm.publish(convert.float64_msg(stages[i].shaft_rpm))

    def _on_cycle(self, msg: ForecastCycle) -> None:
        def take(m: ForecastCycle) -> None:
            for name, payload in self.state.on_cycle(convert.cycle_from_msg(m)):
                self.feed.publish(name, payload)
        self._guard(topics.FORECAST_CYCLE, take, msg)

    def _on_slice(self, msg: ForecastSlice) -> None:
        def take(m: ForecastSlice) -> None:
            view = convert.slice_view_from_msg(m, int(self._p("forecast_max_cells")))
            for name, payload in self.state.on_slice(str(m.cycle_id), view):
                self.feed.publish(name, payload)
                _return_freed_memory()  # a cycle is complete
        self._guard(topics.FORECAST_SLICES, take, msg)

    # ------------------------------------------------------------------ outputs
    def _push_ship(self) -> None:
        if not self._ship_dirty:
            return
        self._ship_dirty = False
        event, self._track_sent = self.state.ship_event(self._track_sent)
        if event is not None:
            event[1]["stats"]["feed"] = self.feed.stats()
            self.feed.publish(*event)

    def _push_stats(self) -> None:
        stats = self.state.stats()
        stats["feed"] = self.feed.stats()
        self.feed.publish("stats", stats)

    def _publish_geojson(self) -> None:
        if self._fox:
            self.pub_geojson.publish(convert.geojson_msg(self.state.geojson()))
            self._geojson_dirty = False

    def _publish_geojson_if_dirty(self) -> None:
        if self._geojson_dirty:
            self._publish_geojson()

    # ------------------------------------------------------------------ page routes
    def _chart_box(self) -> ChartBox:
        box = self.state.chart_box()
        if box is None:
            return WORLD
        # the chart shows more than the route's box (screen aspect, panning): coast for a wide
        # margin so no clipped land edge shows in view
        margin = max(float(self._p("coast_margin_deg")),
                     0.4 * max(box.lon_max - box.lon_min, box.lat_max - box.lat_min))
        return box.padded(margin).rounded(5.0)

    def _view_box(self) -> ChartBox:
        box = self.state.chart_box()
        return WORLD if box is None else box.padded(2.0)

    def _with_box(self, payload: dict[str, Any]) -> dict[str, Any]:
        b = self._view_box()
        return {**payload, "chart_box": [b.lon_min, b.lon_max, b.lat_min, b.lat_max]}

    def _snapshot(self) -> dict[str, Any]:
        snap = self._with_box(self.state.snapshot())
        snap["stats"]["feed"] = self.feed.stats()
        return snap

    def _coast_json(self) -> bytes:
        want = self._chart_box()
        with self._coast_lock:
            if self._coast is None or not self._coast[0].contains(want):
                self._coast = (want, coastline_json(want))
            return self._coast[1]

    def _warm_coast(self) -> None:
        threading.Thread(target=self._coast_json, name="coast-warm", daemon=True).start()

    def _health(self) -> dict[str, Any]:
        plan, _ = self.state.current_plan()
        return {"ok": True, "plan_id": plan.plan_id if plan else None,
                "feed": self.feed.stats(), "received": self.state.stats()["received"],
                "forecast_slices": {c["cycle_id"]: [c["received"], c["slice_count"]]
                                    for c in self.state.snapshot()["forecast"]["cycles"]},
                "url": self.server.url}

    def destroy_node(self) -> None:
        """Stop the web server with the node."""
        self.server.stop()
        super().destroy_node()


def _return_freed_memory() -> None:
    """Hand the freed slice buffers of a cycle (~90 MB passed through) back to the OS: glibc
    keeps freed blocks otherwise (no-op where libc is not glibc)."""
    import contextlib
    import ctypes

    with contextlib.suppress(OSError, AttributeError):
        ctypes.CDLL("libc.so.6").malloc_trim(0)


def main(args: list[str] | None = None) -> int:
    """Console script `shiproute_display_node`."""
    # A forecast cycle is taken a few slices at a time, not held whole (see dds_profile).
    profile = use_windowed_slice_reader(topics.FORECAST_SLICES)
    rclpy.init(args=args if args is not None else sys.argv)
    try:
        node = DisplayNode()
    except (DisplayError, OSError) as err:
        print(f"shiproute_display_node: {err}", file=sys.stderr)
        rclpy.try_shutdown()
        return 2
    finally:
        forget_profile(profile)
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    spin_until_shutdown(executor, (node,))
    return 0


if __name__ == "__main__":
    sys.exit(main())
