"""Benchmark the bridge display: page load, plan-to-page latency, node memory, live pages.

Real processes: the weather node (bundled March storm), the display node, and this process as
planner and ship (the two sample plans, published through the planner's converters). Debian's
headless chromium loads the page (`page_load_s`: navigation start to the plan and coastline
drawn); each of `--plans` new plans is timed from its publication to the page showing it
(`plan_to_page_s`: median and max); `--clients` raw SSE readers stay connected meanwhile and
must each receive the last plan (`clients`); `display_rss_mb` is the node's peak resident size.
`display_rss_mb` is the largest of the resident sizes sampled after each phase (plan and ship
in, page loaded, plans timed, forecast shown); `display_rss_peak_mb` also covers the moment a
whole forecast cycle (129 slices, ~90 MB) streams in. Targets: page <= 2 s, plan to page <= 1 s,
RSS <= 150 MB.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import socket
import statistics
import sys
import threading
import time
from typing import Any

from shiproute_core.bench_report import print_figures

from shiproute_core import topics

TARGETS = {"page_load_s": 2.0, "plan_to_page_s": 1.0, "display_rss_mb": 150.0}


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class _SseReader(threading.Thread):
    """A page stand-in: reads the live feed and remembers the last plan id it saw."""

    def __init__(self, port: int) -> None:
        super().__init__(daemon=True)
        self.port = port
        self.last_plan = ""
        self.stop = False

    def run(self) -> None:
        with socket.create_connection(("127.0.0.1", self.port), timeout=30) as s:
            s.sendall(b"GET /events HTTP/1.1\r\nHost: bench\r\n\r\n")
            buf = b""
            while not self.stop:
                chunk = s.recv(1 << 16)
                if not chunk:
                    return
                buf += chunk
                while b"\n\n" in buf:
                    frame, buf = buf.split(b"\n\n", 1)
                    for line in frame.split(b"\n"):
                        if line.startswith(b"data: ") and b'"plan_id"' in line:
                            data = json.loads(line[6:])
                            plan = data.get("plan") or {}
                            self.last_plan = plan.get("plan_id", self.last_plan)


def _forecast_complete(port: int) -> bool:
    with socket.create_connection(("127.0.0.1", port), timeout=5) as s:
        s.sendall(b"GET /api/health HTTP/1.1\r\nHost: bench\r\nConnection: close\r\n\r\n")
        data = b""
        while chunk := s.recv(65536):
            data += chunk
    got = json.loads(data.split(b"\r\n\r\n", 1)[1]).get("forecast_slices", {})
    return any(n == total for n, total in got.values())


def _browser() -> Any:
    from selenium import webdriver
    from selenium.webdriver.chrome.options import Options
    from selenium.webdriver.chrome.service import Service

    opts = Options()
    opts.binary_location = "/usr/bin/chromium"
    for a in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
              "--window-size=1600,1000"):
        opts.add_argument(a)
    return webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=opts)


class _DisplayPeer:
    """This process as planner and ship: latched plan publishers and the ship's state on a
    node of its own context, spun on a thread."""

    def __init__(self, domain_id: int) -> None:
        import rclpy
        from rclpy.context import Context
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy

        from shiproute_msgs.msg import RoutePlan, RpmProfile, ShipState

        self.ctx = Context()
        rclpy.init(context=self.ctx, domain_id=domain_id)
        self.node = rclpy.create_node("display_bench", context=self.ctx)
        latched = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE,
                             durability=DurabilityPolicy.TRANSIENT_LOCAL)
        self.pub_plan = self.node.create_publisher(RoutePlan, topics.PLAN_ROUTE, latched)
        self.pub_prof = self.node.create_publisher(RpmProfile, topics.PLAN_RPM_PROFILE, latched)
        self.pub_ship = self.node.create_publisher(ShipState, topics.SHIP_STATE, 10)
        self.ship_state_type = ShipState
        self.executor = SingleThreadedExecutor(context=self.ctx)
        self.executor.add_node(self.node)
        self.stop_spin = threading.Event()
        self.spin = threading.Thread(target=self._spin_loop, daemon=True)

    def _spin_loop(self) -> None:
        while not self.stop_spin.is_set():
            self.executor.spin_once(timeout_sec=0.05)

    def subscribed(self) -> bool:
        """True once the display listens to the ship and the plan."""
        return (self.pub_ship.get_subscription_count() > 0
                and self.pub_plan.get_subscription_count() > 0)

    def publish(self, plan: Any, plan_id: str, trigger: str) -> None:
        """A plan and its RPM profile, as the planner publishes them."""
        from shiproute_planner.ros.convert import plan_to_msg, plan_to_rpm_profile, time_msg

        msg = plan_to_msg(plan, time_msg(time.time()))
        msg.plan_id, msg.trigger = plan_id, trigger
        prof = plan_to_rpm_profile(plan, time_msg(time.time()))
        prof.plan_id = plan_id
        self.pub_prof.publish(prof)
        self.pub_plan.publish(msg)

    def ship_day(self, plan: Any) -> None:
        """A day of ship states, half-hourly, along `plan`."""
        from shiproute_display.geometry import position_at
        from shiproute_display.ros.convert import plan_from_msg
        from shiproute_planner.ros.convert import plan_to_msg, time_msg

        view = plan_from_msg(plan_to_msg(plan, time_msg(time.time())))
        t = plan.departure_s
        for _ in range(48):
            lat, lon, i = position_at(view, t)
            m = self.ship_state_type()
            m.header.stamp = time_msg(t)
            m.latitude_deg, m.longitude_deg, m.sog_kn, m.heading_deg = lat, lon, 17.5, 70.0
            m.shaft_rpm = plan.waypoints[i].shaft_rpm
            self.pub_ship.publish(m)
            time.sleep(0.01)  # the publisher keeps 10: let each one go out
            t += 1800.0

    def close(self) -> None:
        """Stop spinning and shut the context down."""
        self.stop_spin.set()
        if self.spin.is_alive():
            self.spin.join(2)
        self.node.destroy_node()
        self.ctx.try_shutdown()


class _RssProbe:
    """The display node's resident size: after each phase, and its peak sampled every 0.1 s."""

    def __init__(self, pid: int) -> None:
        self.pid = pid
        self.phases: dict[str, float] = {}
        self.peak_mb = 0.0
        self.sampling = True

    def start(self) -> None:
        """Sample the peak on a thread (it covers the forecast cycle's burst)."""
        threading.Thread(target=self._sample, daemon=True).start()

    def _sample(self) -> None:
        import psutil

        proc = psutil.Process(self.pid)
        while self.sampling:
            try:
                self.peak_mb = max(self.peak_mb, proc.memory_info().rss / 2**20)
            except psutil.Error:
                return
            time.sleep(0.1)

    def phase(self, name: str) -> None:
        """The resident size now, under `name`."""
        import psutil

        with contextlib.suppress(psutil.Error):
            self.phases[name] = round(psutil.Process(self.pid).memory_info().rss / 2**20, 1)


def _open_page(driver: Any, port: int) -> tuple[float, float]:
    """(page load [s] to the plan and coastline drawn, navigation start to now [s])."""
    from shiproute_bringup.rosproc import wait_until

    t0 = time.monotonic()
    driver.get(f"http://127.0.0.1:{port}/")
    wait_until(lambda: driver.execute_script(
        "return !!(window.__display && window.__display.lastPlanId && "
        "window.__display.coastDrawn)"), 30, interval_s=0.01, what="page drawn")
    page_load_s = time.monotonic() - t0
    nav_s = driver.execute_script(
        "const n=performance.getEntriesByType('navigation')[0];"
        "return (performance.now() - n.startTime)/1000;")
    return page_load_s, nav_s


def _time_plans(peer: _DisplayPeer, driver: Any, plans: list[Any], n_plans: int) -> list[float]:
    """Seconds from each new plan's publication to the page showing it."""
    from shiproute_bringup.rosproc import wait_until

    lat_s = []
    for k in range(n_plans):
        pid = f"bench-{k:03d}"
        t_pub = time.monotonic()
        peer.publish(plans[(k + 1) % 2], pid, "new forecast cycle bench")

        def on_page(pid: str = pid) -> bool:
            return bool(driver.execute_script("return window.__display.lastPlanId") == pid)

        wait_until(on_page, 10, interval_s=0.005, what=f"plan {pid} on the page")
        lat_s.append(time.monotonic() - t_pub)
        time.sleep(0.3)
    return lat_s


def _screenshot(driver: Any, plan: Any, path: str) -> None:
    """The page with the time slider 2.5 days after `plan`'s departure, saved to `path`."""
    driver.execute_script(
        "const s=document.getElementById('time-slider');"
        f"s.value=Math.round({plan.departure_s + 2.5 * 86400}/3600);"
        "s.dispatchEvent(new Event('input'));")
    time.sleep(1.0)
    driver.save_screenshot(path)


def _figures(page_load_s: float, nav_s: float, lat_s: list[float], n_plans: int,
             probe: _RssProbe, clients: int) -> dict[str, Any]:
    """The JSON-ready result and whether it meets the targets."""
    phases = probe.phases
    result: dict[str, Any] = {
        "page_load_s": round(page_load_s, 3), "page_load_nav_s": round(nav_s, 3),
        "plan_to_page_s": round(statistics.median(lat_s), 3),
        "plan_to_page_max_s": round(max(lat_s), 3), "plans": n_plans,
        "display_rss_mb": round(max(v for k, v in phases.items() if k != "cycle_burst_peak"),
                                1),
        "display_rss_peak_mb": round(probe.peak_mb, 1), "rss_mb_by_phase": phases,
        "clients": clients,
        "targets": TARGETS,
    }
    result["peak_within_rss_target"] = probe.peak_mb <= TARGETS["display_rss_mb"]
    result["meets_targets"] = (result["page_load_s"] <= TARGETS["page_load_s"]
                               and result["plan_to_page_max_s"] <= TARGETS["plan_to_page_s"]
                               and result["display_rss_mb"] <= TARGETS["display_rss_mb"])
    return result


def run(n_plans: int, n_clients: int, screenshot: str | None) -> dict[str, Any]:
    """Run the benchmark; returns the JSON-ready result."""
    from shiproute_display.samples import load_sample_plan

    from shiproute_bringup.rosproc import RosProcess, random_bench_domain_id, wait_until

    plans = [load_sample_plan(n) for n in ("plan_cycle1", "plan_cycle2")]
    dom, port = random_bench_domain_id(), _free_port()
    weather = RosProcess.script("shiproute_weather_node", "--ros-args", "-p",
                                "scenario:=storm_march", domain_id=dom, name="weather")
    display = RosProcess.script("shiproute_display_node", "--ros-args", "-p", f"port:={port}",
                                domain_id=dom, name="display")
    peer = _DisplayPeer(dom)
    probe = _RssProbe(display.proc.pid)
    driver = None
    try:
        display.wait_for_line(r"bridge display on http", 60)
        peer.spin.start()
        probe.start()
        wait_until(peer.subscribed, 30, what="display subscribed")
        peer.publish(plans[0], plans[0].plan_id, "first ship state")
        peer.ship_day(plans[0])
        # steady state before the page opens: plan, ship and the whole forecast cycle taken in
        wait_until(lambda: _forecast_complete(port), 120, interval_s=0.2,
                   what="forecast cycle at the display")
        time.sleep(1.0)
        probe.phase("plan_ship_forecast")
        driver = _browser()
        page_load_s, nav_s = _open_page(driver, port)
        probe.phase("page_loaded")
        readers = [_SseReader(port) for _ in range(n_clients)]
        for r in readers:
            r.start()
        time.sleep(0.5)
        lat_s = _time_plans(peer, driver, plans, n_plans)
        probe.phase("plans_timed")
        last = f"bench-{n_plans - 1:03d}"
        wait_until(lambda: all(r.last_plan == last for r in readers), 10, what="readers")
        got = sum(r.last_plan == last for r in readers) + 1  # + the browser
        page = driver
        wait_until(lambda: "/129" in page.find_element("id", "st-forecast").text, 60,
                   what="forecast on the page")
        probe.phase("forecast_shown")
        if screenshot:
            _screenshot(driver, plans[1], screenshot)
        for r in readers:
            r.stop = True
        probe.sampling = False
        return _figures(page_load_s, nav_s, lat_s, n_plans, probe, got)
    finally:
        probe.sampling = False
        if driver is not None:
            driver.quit()
        peer.close()
        display.stop()
        weather.stop()


def main(argv: list[str] | None = None) -> int:
    """Entry point of `shiproute bench display`."""
    p = argparse.ArgumentParser(prog="shiproute bench display", description=__doc__.splitlines()[0])
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--plans", type=int, default=10, help="new plans timed to the page")
    p.add_argument("--clients", type=int, default=8, help="extra live-feed clients")
    p.add_argument("--screenshot", help="save a screenshot of the page to this PNG file")
    args = p.parse_args(argv)
    if args.plans < 1 or args.clients < 0:
        p.error("--plans must be >= 1 and --clients >= 0")
    res = run(args.plans, args.clients, args.screenshot)
    print_figures(res, args.json)
    sys.stdout.flush()
    return 0
