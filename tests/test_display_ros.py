"""The bridge display across processes and in a real headless browser (Debian chromium).

Real nodes: the weather node serves the bundled March storm, the display node serves its page,
and this process plays planner and ship with two plans the real planner made (fixtures in
src/shiproute_display/test/data, published through the planner's own converters). One browser
session checks: the page shows the published plan (waypoint count, ETA), a new plan replaces
it within 2 s, the time slider moves the planned-position marker to the arrival node at the
ETA, the screenshot shows a chart (land, sea and route colours, not a blank page), the schedule
highlights the stage in force, malformed messages are counted on the page. Then: the server
refuses `..` paths, unknown routes and other methods; clients that never read do not grow the
node's memory; the Foxglove topics carry valid GeoJSON, the ship fix and the planned RPM; the
Foxglove layout parses and names only topics that exist.
"""

from __future__ import annotations

import io
import json
import math
import os
import socket
import sys
import threading
import time
from pathlib import Path
from typing import Any

import pytest

from shiproute_core import topics

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "src/shiproute_display/test"))

pytestmark = [pytest.mark.ros, pytest.mark.slow]

rclpy = pytest.importorskip("rclpy")
pytest.importorskip("foxglove_msgs.msg")
webdriver = pytest.importorskip("selenium.webdriver")
if not (Path("/usr/bin/chromium").exists() and Path("/usr/bin/chromedriver").exists()):
    pytest.skip("Debian chromium + chromium-driver not installed (ros2_ws/bootstrap.sh installs "
                "them)", allow_module_level=True)

import psutil  # noqa: E402
from display_fixtures import load_plan, plan_messages  # noqa: E402
from geojson_check import check_geojson  # noqa: E402
from rclpy.executors import SingleThreadedExecutor  # noqa: E402
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy  # noqa: E402
from rosproc import RosProcess, random_domain_id, ros_context, wait_until  # noqa: E402
from selenium.webdriver.chrome.options import Options  # noqa: E402
from selenium.webdriver.chrome.service import Service  # noqa: E402
from selenium.webdriver.common.by import By  # noqa: E402
from sensor_msgs.msg import NavSatFix  # noqa: E402
from std_msgs.msg import Float64  # noqa: E402

from foxglove_msgs.msg import GeoJSON  # noqa: E402
from shiproute_msgs.msg import RoutePlan, RpmProfile, ShipState  # noqa: E402

LAYOUT = REPO / "src/shiproute_display/shiproute_display/foxglove_layout.json"
LATCHED = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE,
                     durability=DurabilityPolicy.TRANSIENT_LOCAL)


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Bridge:
    """Planner and ship stand-in (publishers) and Foxglove listener, spun in a thread."""

    def __init__(self, ctx: Any) -> None:
        self.node = rclpy.create_node("display_test_bridge", context=ctx)
        self.pub_plan = self.node.create_publisher(RoutePlan, topics.PLAN_ROUTE, LATCHED)
        self.pub_profile = self.node.create_publisher(RpmProfile, topics.PLAN_RPM_PROFILE,
                                                      LATCHED)
        self.pub_ship = self.node.create_publisher(ShipState, topics.SHIP_STATE, 10)
        self.geojson: list[str] = []
        self.ship_fix: list[NavSatFix] = []
        self.planned_rpm: list[float] = []
        self.node.create_subscription(GeoJSON, topics.DISPLAY_GEOJSON,
                                      lambda m: self.geojson.append(m.geojson), LATCHED)
        self.node.create_subscription(NavSatFix, topics.DISPLAY_SHIP_FIX,
                                      self.ship_fix.append, 10)
        self.node.create_subscription(Float64, topics.DISPLAY_PLANNED_RPM,
                                      lambda m: self.planned_rpm.append(m.data), 10)
        self.executor = SingleThreadedExecutor(context=ctx)
        self.executor.add_node(self.node)
        self._stop = False
        self.thread = threading.Thread(target=self._spin, daemon=True)
        self.thread.start()

    def _spin(self) -> None:
        while not self._stop:
            self.executor.spin_once(timeout_sec=0.05)

    def publish_plan(self, plan: Any, trigger: str = "") -> None:
        msg, profile = plan_messages(plan, time.time(), trigger)
        self.pub_profile.publish(profile)
        self.pub_plan.publish(msg)

    def publish_ship(self, lat: float, lon: float, t_s: float, rpm: float) -> None:
        m = ShipState()
        m.header.stamp.sec = int(t_s)
        m.header.stamp.nanosec = int((t_s % 1) * 1e9)
        m.header.frame_id = "wgs84"
        m.mmsi = 440123456
        m.latitude_deg, m.longitude_deg = lat, lon
        m.sog_kn, m.cog_deg, m.heading_deg, m.stw_kn = 17.0, 60.0, 60.0, 17.0
        m.shaft_rpm, m.fuel_rate_t_per_h = rpm, 2.3
        m.draft_fore_m = m.draft_aft_m = 12.0
        self.pub_ship.publish(m)

    def close(self) -> None:
        self._stop = True
        self.thread.join(2)
        self.node.destroy_node()


@pytest.fixture(scope="module")
def world():
    dom = random_domain_id()
    port = free_port()
    plans = (load_plan("plan_cycle1"), load_plan("plan_cycle2"))
    weather = RosProcess.script("shiproute_weather_node", "--ros-args", "-p",
                                "scenario:=storm_march", domain_id=dom, name="weather")
    display = RosProcess.script("shiproute_display_node", "--ros-args", "-p", f"port:={port}",
                                domain_id=dom, name="display")
    try:
        display.wait_for_line(r"bridge display on http://127\.0\.0\.1:\d+/", 60)
        with ros_context(dom) as ctx:
            bridge = Bridge(ctx)
            try:
                yield {"port": port, "url": f"http://127.0.0.1:{port}/", "bridge": bridge,
                       "plans": plans, "display": display, "weather": weather}
            finally:
                bridge.close()
    finally:
        display.stop()
        weather.stop()


@pytest.fixture(scope="module")
def browser():
    opts = Options()
    opts.binary_location = "/usr/bin/chromium"
    for a in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
              "--window-size=1600,1000", "--force-device-scale-factor=1"):
        opts.add_argument(a)
    driver = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=opts)
    try:
        yield driver
    finally:
        driver.quit()


def _text(driver: Any, el_id: str) -> str:
    return driver.find_element(By.ID, el_id).text


def _ship_along(bridge: Bridge, plan: Any, hours: float, step_h: float = 0.5) -> float:
    """Ship states on the plan from departure for `hours`; returns the last time."""
    from shiproute_display.geometry import position_at
    from shiproute_display.ros.convert import plan_from_msg

    view = plan_from_msg(plan_messages(plan, time.time())[0])
    t = plan.departure_s
    for _ in range(int(hours / step_h) + 1):
        lat, lon, i = position_at(view, t)
        bridge.publish_ship(lat, lon, t, plan.waypoints[i].shaft_rpm)
        t += step_h * 3600
        time.sleep(0.005)
    return t - step_h * 3600


def test_page_live_plan_slider_screenshot(world, browser, tmp_path):
    bridge, (p1, p2) = world["bridge"], world["plans"]
    bridge.publish_plan(p1, "first ship state")
    last_t = _ship_along(bridge, p1, 30.0)
    t0 = time.monotonic()
    browser.get(world["url"])
    wait_until(lambda: browser.execute_script(
        "return window.__display && window.__display.lastPlanId") == p1.plan_id, 15,
        what="first plan on the page")
    wait_until(lambda: browser.execute_script("return window.__display.coastDrawn"), 15,
               what="coastline drawn")
    load_s = time.monotonic() - t0
    assert _text(browser, "wp-count") == str(len(p1.waypoints))
    eta_s = float(browser.find_element(By.ID, "eta").get_attribute("data-eta-s"))
    assert abs(eta_s - p1.eta_s) < 1.0
    expected_eta = time.strftime("%Y-%m-%d %H:%M", time.gmtime(round(p1.eta_s / 60) * 60))
    assert _text(browser, "eta").startswith(time.strftime("%Y-%m-%d %H:", time.gmtime(p1.eta_s)))
    assert expected_eta[:13] in _text(browser, "eta")
    assert load_s < 10.0

    # the schedule has one row per leg and highlights the stage in force at the ship's time
    rows = browser.find_elements(By.CSS_SELECTOR, "#schedule tbody tr")
    assert len(rows) == len(p1.waypoints) - 1
    stage = max(i for i, w in enumerate(p1.waypoints[:-1]) if w.time_s <= last_t)
    wait_until(lambda: browser.execute_script(
        "const r=document.querySelectorAll('#schedule tbody tr');"
        f"return r.length > {stage} && r[{stage}].classList.contains('current');"), 5,
        what="current stage highlighted")
    cd = _text(browser, "countdown")
    assert f"Stage {stage + 1}" in cd and ("Next RPM change" in cd or "No RPM change" in cd)

    # the forecast arrives from the weather node and is offered at the slider's time
    wait_until(lambda: "129/129" in _text(browser, "st-forecast"), 60, what="forecast cycle")

    # new plan replaces the old within 2 s; the old one stays as the faded previous plan
    t_pub = time.monotonic()
    bridge.publish_plan(p2, "new forecast cycle storm_march_cycle2")
    wait_until(lambda: browser.execute_script("return window.__display.lastPlanId")
               == p2.plan_id, 5, interval_s=0.02, what="second plan on the page")
    replace_s = time.monotonic() - t_pub
    assert replace_s <= 2.0, f"new plan took {replace_s:.2f} s to replace the old one"
    assert _text(browser, "wp-count") == str(len(p2.waypoints))
    assert browser.find_elements(By.ID, "previous-plan")
    cells = browser.execute_script(
        "const r=document.querySelectorAll('#history tbody tr');"
        "return [r.length, ...[...r[0].querySelectorAll('td')].map(td => td.textContent)];")
    n_rows, cells = cells[0], cells[1:]
    assert n_rows == 2 and cells[2] == "new cycle"
    assert cells[1] == p2.plan_id and cells[3] == p2.cycle_id
    assert abs(float(cells[4]) - (p2.eta_s - p1.eta_s) / 3600.0) <= 0.0051  # dETA h
    assert abs(float(cells[5]) - (p2.total_fuel_t - p1.total_fuel_t)) <= 0.051  # dfuel t

    # the slider moves the planned-position marker; at its end it sits on the arrival node
    read = ("const m=document.getElementById('plan-marker');"
            "const n=document.querySelectorAll('#layer-plan circle.waypoint'), a=n[n.length-1];"
            "return [+m.getAttribute('cx'), +m.getAttribute('cy'),"
            " +a.getAttribute('cx'), +a.getAttribute('cy')];")
    before = browser.execute_script(read)[:2]
    browser.execute_script(
        "const s=document.getElementById('time-slider'); s.value=s.max;"
        "s.dispatchEvent(new Event('input'));")
    mx, my, ax, ay = browser.execute_script(read)
    assert math.dist(before, (mx, my)) > 50
    assert math.dist((mx, my), (ax, ay)) < 1.5  # at the ETA the marker sits on the arrival
    assert "forecast valid" in _text(browser, "time-label") or "no forecast" in _text(
        browser, "time-label")

    # a screenshot shows a chart: land and sea colours, the route, not a blank page
    browser.execute_script(
        "const s=document.getElementById('time-slider');"
        f"s.value=Math.round({p2.departure_s + 3 * 86400}/3600);"
        "s.dispatchEvent(new Event('input'));")
    time.sleep(0.8)  # forecast slice fetch + redraw
    _check_screenshot(browser, tmp_path)

    # a malformed plan is counted on the page and changes nothing else
    bad, _ = plan_messages(p2, time.time())
    bad.plan_id = "broken"
    bad.waypoints = bad.waypoints[:1]
    bridge.pub_plan.publish(bad)
    wait_until(lambda: "malformed 1" in _text(browser, "st-malformed"), 5,
               what="malformed count on the page")
    assert browser.execute_script("return window.__display.lastPlanId") == p2.plan_id


def _check_screenshot(browser: Any, tmp_path: Path) -> None:
    import numpy as np
    from PIL import Image

    for theme in ("night", "day"):
        browser.execute_script(f"document.documentElement.dataset.theme='{theme}';"
                               "window.dispatchEvent(new Event('resize'));")
        browser.execute_script("document.getElementById('theme-btn').click();"
                               "document.getElementById('theme-btn').click();")
        time.sleep(0.3)
        png = browser.get_screenshot_as_png()
        (tmp_path / f"display_{theme}.png").write_bytes(png)
        if os.environ.get("SHIPROUTE_DISPLAY_SHOTS"):
            Path(os.environ["SHIPROUTE_DISPLAY_SHOTS"], f"display_{theme}.png").write_bytes(png)
        img = np.asarray(Image.open(io.BytesIO(png)).convert("RGB")).astype(int)
        chart = browser.find_element(By.ID, "chart-wrap").rect
        x0, y0 = int(chart["x"]), int(chart["y"])
        px = img[y0:y0 + int(chart["height"]), x0:x0 + int(chart["width"])].reshape(-1, 3)
        assert px.std(axis=0).mean() > 10, f"{theme}: chart looks blank"
        land = {"day": (0xe6, 0xdc, 0xc3), "night": (0x1b, 0x1a, 0x14)}[theme]
        land_frac = float((np.abs(px - land).max(axis=1) <= 3).mean())
        assert land_frac > 0.01, f"{theme}: no coastline/land drawn ({land_frac:.3%})"
        # route legs are viridis colours: purple..yellow, present in a few hundred pixels
        vivid = ((px[:, 1] > 150) & (px[:, 0] > 180) & (px[:, 2] < 90)).sum() + (
            (px[:, 0] > 50) & (px[:, 0] < 80) & (px[:, 1] < 20) & (px[:, 2] > 70)).sum()
        teal = (np.abs(px - (0x21, 0x91, 0x8c)).max(axis=1) <= 12).sum()
        assert vivid + teal > 150, f"{theme}: route not visible"


def _http(port: int, request: bytes) -> tuple[int, bytes]:
    with socket.create_connection(("127.0.0.1", port), timeout=5) as s:
        s.sendall(request)
        data = b""
        while chunk := s.recv(65536):
            data += chunk
            if b"\r\n\r\n" in data and len(data) > 4096:
                break
    status = int(data.split(b" ", 2)[1])
    return status, data


@pytest.mark.parametrize("path,status", [
    ("/../etc/passwd", 400), ("/web/../../pyproject.toml", 400), ("/%2e%2e/%2e%2e/etc/passwd", 400),
    ("/..%2fnode.py", 400), ("/static/..\\node.py", 400),
    ("//etc/passwd", 404),  # http.server folds a leading // to /: an unknown route
    ("/web/", 404), ("/node.py", 404), ("/shiproute_display/", 404), ("/api", 404),
    ("/api/forecast?cycle=x&index=0", 404), ("/api/forecast?index=a", 400), ("/", 200),
    ("/app.js", 200), ("/api/health", 200),
])
def test_server_serves_only_its_own_routes(world, path, status):
    code, data = _http(world["port"], f"GET {path} HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n"
                       .encode())
    assert code == status, data[:300]
    if status != 200:
        assert b"root:" not in data and b"import" not in data


def test_server_refuses_other_methods(world):
    code, _ = _http(world["port"], b"POST / HTTP/1.1\r\nHost: x\r\nContent-Length: 0\r\n"
                    b"Connection: close\r\n\r\n")
    assert code == 405


def _health(port: int) -> dict:
    return json.loads(_http(port, b"GET /api/health HTTP/1.1\r\nHost: x\r\n"
                            b"Connection: close\r\n\r\n")[1].split(b"\r\n\r\n", 1)[1])


def test_clients_that_never_read_do_not_grow_memory(world, browser):
    """Four clients connect to the live feed and never read while plans flood in: each holds at
    most `client_queue_depth` (64) events in the node (an unbounded queue reaches hundreds),
    the node's memory stays flat, the stalled clients are cut off, the browser stays live."""
    bridge, (p1, p2) = world["bridge"], world["plans"]
    port = world["port"]
    proc = psutil.Process(world["display"].proc.pid)
    if not browser.current_url.startswith(world["url"]):
        browser.get(world["url"])
        wait_until(lambda: browser.execute_script("return !!window.__display"), 10,
                   what="page loaded")

    def storm(n: int) -> None:
        for k in range(n):  # distinct plan ids: each is a new plan (~15 kB event)
            msg, _profile = plan_messages(p1 if k % 2 else p2, time.time())
            msg.plan_id = f"flood-{n}-{k}"
            bridge.pub_plan.publish(msg)
            time.sleep(0.004)

    storm(150)  # warm-up: history and caches at their bounds before the baseline
    time.sleep(1.0)
    rss0 = proc.memory_info().rss
    stalled = []
    for _ in range(4):
        s = socket.create_connection(("127.0.0.1", port))
        s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
        s.sendall(b"GET /events HTTP/1.1\r\nHost: x\r\n\r\n")
        stalled.append(s)  # never read
    peak = {"rss": rss0, "queued_max": 0}
    done = threading.Event()

    def sample() -> None:
        while not done.is_set():
            peak["rss"] = max(peak["rss"], proc.memory_info().rss)
            peak["queued_max"] = max(peak["queued_max"], _health(port)["feed"]["queued_max"])
            time.sleep(0.1)

    sampler = threading.Thread(target=sample, daemon=True)
    sampler.start()
    storm(600)
    wait_until(lambda: _health(port)["plan_id"] == "flood-600-599", 30, what="flood taken")
    done.set()
    sampler.join(2)
    grown_mb = (peak["rss"] - rss0) / 2**20
    assert peak["queued_max"] <= 64, f"a stalled client held {peak['queued_max']} events"
    assert peak["queued_max"] >= 32, "the flood never filled a stalled client's queue"
    assert grown_mb < 15.0, f"display RSS grew {grown_mb:.1f} MB with 4 stalled clients"
    # the stalled clients are cut off (send timeout) while the browser page keeps up
    wait_until(lambda: _health(port)["feed"]["clients"] == 1, 15, what="stalled clients cut")
    for s in stalled:
        s.close()
    wait_until(lambda: browser.execute_script("return window.__display.lastPlanId")
               == "flood-600-599", 10, what="page still live")


def _check_recording(world: dict, tmp_path: Path) -> None:
    """`shiproute bag record` stores the GeoJSON topic with Foxglove's schema, valid messages."""
    from mcap.reader import make_reader

    out = tmp_path / "rec"
    rec = RosProcess.script("shiproute", "bag", "record", str(out), topics.DISPLAY_GEOJSON,
                            topics.DISPLAY_SHIP_FIX, "--duration", "8",
                            domain_id=world["display"].domain_id, name="record")
    assert rec.wait(40) == 0, rec.output
    (mcap_file,) = out.glob("*.mcap")
    with mcap_file.open("rb") as fh:
        reader = make_reader(fh)
        summary = reader.get_summary()
        schemas = {s.name: s.data.decode() for s in summary.schemas.values()}
        assert schemas["foxglove_msgs/msg/GeoJSON"].strip().endswith("string geojson")
        assert "sensor_msgs/msg/NavSatFix" in schemas
        texts = []
        for _schema, channel, message in reader.iter_messages(topics=[topics.DISPLAY_GEOJSON]):
            assert channel.message_encoding == "cdr"
            # CDR of a message with one string: 4-byte encapsulation, uint32 length, bytes + NUL
            n = int.from_bytes(message.data[4:8], "little")
            texts.append(message.data[8:8 + n - 1].decode())
    assert texts, "no GeoJSON message recorded (the topic is latched: one at least)"
    for text in texts:
        check_geojson(json.loads(text))


def test_foxglove_topics_and_layout(world, tmp_path):
    bridge, (_, p2) = world["bridge"], world["plans"]
    wait_until(lambda: bridge.geojson, 10, what="GeoJSON message")
    wait_until(lambda: bridge.ship_fix and bridge.planned_rpm, 10, what="NavSatFix + RPM")
    for text in bridge.geojson[-3:]:
        names = check_geojson(json.loads(text))
        assert any(n.startswith("plan ") for n in names) and "own ship" in names
    # the planned RPM is the schedule's RPM at the ship's time (from the plan's legs)
    t = p2.departure_s + 3600.0
    from shiproute_display.geometry import position_at
    from shiproute_display.ros.convert import plan_from_msg

    lat, lon, i = position_at(plan_from_msg(plan_messages(p2, time.time())[0]), t)
    n = len(bridge.planned_rpm)
    bridge.publish_plan(p2)  # current again (the flood left another plan current)
    time.sleep(0.3)
    bridge.publish_ship(lat, lon, t, 70.0)
    wait_until(lambda: len(bridge.planned_rpm) > n, 5, what="planned RPM")
    wait_until(lambda: abs(bridge.planned_rpm[-1] - p2.waypoints[i].shaft_rpm) < 1e-6, 5,
               what="planned RPM of the stage")
    fix = bridge.ship_fix[-1]
    assert abs(fix.latitude - lat) < 1e-9 and abs(fix.longitude - lon) < 1e-9

    _check_recording(world, tmp_path)

    layout = json.loads(LAYOUT.read_text())
    live = {name for name, _ in bridge.node.get_topic_names_and_types()}
    named = _layout_topics(layout)
    assert named and named <= live, f"layout names missing topics {named - live}"
    panels = {k.split("!")[0] for k in layout["configById"]}
    assert {"map", "Plot"} <= panels
    # the bridge node must also publish the plan route topic for the RawMessages panel
    assert topics.PLAN_ROUTE in named


def _layout_topics(layout: dict) -> set[str]:
    """Topic names a Foxglove layout refers to (plot paths and map topic settings)."""
    out: set[str] = set()
    for cfg in layout["configById"].values():
        for p in cfg.get("paths", []):
            out.add(p["value"].split(".")[0])
        out.update(cfg.get("topicColors", {}))
        if cfg.get("topicPath"):
            out.add(cfg["topicPath"].split(".")[0])
        if cfg.get("followTopic"):
            out.add(cfg["followTopic"])
        out.update(cfg.get("topics", []))
    return out
