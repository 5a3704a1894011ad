"""An ensemble cycle and an ensemble plan in the bridge display, in a real headless browser.

Real nodes: the weather node streams the bundled 20-member `storm_march_ensemble` (200 slices:
20 members x 10 valid times within its max_slices budget), the display node serves the page,
and this process publishes the plan the real planner made on that ensemble under CVaR 0.9
(fixture `plan_ensemble`) through the planner's own converters. The page must show 20 members
and 10 valid times (not 200 times), a member selector (P90 of the members or one member), the
members' Hs-peak tracks, the plan's P10/P50/P90 of fuel and ETA and its probabilities, and the
time slider must still run over valid times.
"""

from __future__ import annotations

import json
import sys
import time
import urllib.request
from pathlib import Path
from typing import Any

import pytest

from shiproute_core import topics

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "src/shiproute_display/test"))

pytestmark = [pytest.mark.ros, pytest.mark.slow]

rclpy = pytest.importorskip("rclpy")
webdriver = pytest.importorskip("selenium.webdriver")
if not (Path("/usr/bin/chromium").exists() and Path("/usr/bin/chromedriver").exists()):
    pytest.skip("Debian chromium + chromium-driver not installed (ros2_ws/bootstrap.sh installs "
                "them)", allow_module_level=True)

from display_fixtures import load_plan, plan_messages  # noqa: E402
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy  # noqa: E402
from rosproc import RosProcess, random_domain_id, ros_context, wait_until  # noqa: E402
from selenium.webdriver.chrome.options import Options  # noqa: E402
from selenium.webdriver.chrome.service import Service  # noqa: E402
from selenium.webdriver.common.by import By  # noqa: E402
from selenium.webdriver.support.ui import Select  # noqa: E402
from test_display_ros import free_port  # noqa: E402

from shiproute_msgs.msg import RoutePlan, RpmProfile, ShipState  # noqa: E402

LATCHED = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE,
                     durability=DurabilityPolicy.TRANSIENT_LOCAL)


def _text(driver: Any, el_id: str) -> str:
    return driver.find_element(By.ID, el_id).text


def _publish(ctx: Any, plan: Any) -> Any:
    node = rclpy.create_node("display_ensemble_test", context=ctx)
    pub_plan = node.create_publisher(RoutePlan, topics.PLAN_ROUTE, LATCHED)
    pub_profile = node.create_publisher(RpmProfile, topics.PLAN_RPM_PROFILE, LATCHED)
    pub_ship = node.create_publisher(ShipState, topics.SHIP_STATE, 10)
    msg, profile = plan_messages(plan, time.time())
    pub_profile.publish(profile)
    pub_plan.publish(msg)
    ship = ShipState()
    t = plan.departure_s + 3600.0  # the ship one hour out: the page's clock is the ship's
    ship.header.stamp.sec = int(t)
    ship.header.frame_id = "wgs84"
    w = plan.waypoints[0]
    ship.latitude_deg, ship.longitude_deg = w.lat_deg, w.lon_deg
    ship.sog_kn = ship.stw_kn = 17.0
    for _ in range(5):
        pub_ship.publish(ship)
        time.sleep(0.2)
    return node


def test_ensemble_cycle_and_plan_in_the_browser(tmp_path: Path) -> None:
    dom, port = random_domain_id(), free_port()
    plan = load_plan("plan_ensemble")
    opts = Options()
    opts.binary_location = "/usr/bin/chromium"
    for a in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
              "--window-size=1600,1000"):
        opts.add_argument(a)
    with RosProcess.script("shiproute_weather_node", "--ros-args", "-p",
                           "scenario:=storm_march_ensemble", domain_id=dom,
                           name="weather") as weather, \
            RosProcess.script("shiproute_display_node", "--ros-args", "-p", f"port:={port}",
                              domain_id=dom, name="display") as display, \
            ros_context(dom) as ctx:
        display.wait_for_line(r"bridge display on http://127\.0\.0\.1:\d+/", 60)
        node = _publish(ctx, plan)
        driver = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=opts)
        try:
            driver.get(f"http://127.0.0.1:{port}/")
            weather.wait_for_line(r"published cycle \S+: 200 slices of 20 member", 240)
            wait_until(lambda: "200/200 slices · 20 members × 10 times"
                       in _text(driver, "st-forecast"), 120, what="the ensemble cycle")
            wait_until(lambda: driver.execute_script("return window.__display.lastPlanId")
                       == plan.plan_id, 30, what="the ensemble plan")
            snap = json.loads(urllib.request.urlopen(
                f"http://127.0.0.1:{port}/api/snapshot", timeout=10).read())
            cyc = snap["forecast"]["cycles"][0]
            assert cyc["members"] == 20 and len(cyc["times_s"]) == 10
            assert len(cyc["tracks"]) == 20
            # the member selector: the members' P90 first, then each member
            sel = Select(driver.find_element(By.ID, "member-view"))
            assert len(sel.options) == 21 and sel.options[0].text == "P90 of 20 members"
            assert len(driver.find_elements(By.CSS_SELECTOR, "#layer-tracks path")) == 20
            wait_until(lambda: "P90 of 20 members" in _text(driver, "time-label"), 15,
                       what="the P90 view at the slider's time")
            sel.select_by_value("3")
            wait_until(lambda: "member 3" in _text(driver, "time-label"), 10, what="member 3")
            # the slider still runs over valid times: 42 h apart, whatever the members
            valid = [time.strftime("%H:%M", time.gmtime(t)) for t in cyc["times_s"]]
            slider = driver.find_element(By.ID, "time-slider")
            for hours in (0, 50, 100):
                driver.execute_script(
                    "const s = arguments[0]; s.value = arguments[1];"
                    "s.dispatchEvent(new Event('input'));", slider,
                    int(plan.departure_s // 3600) + hours)
                label = _text(driver, "time-label")
                assert "forecast valid" in label and any(v in label for v in valid), label
            # the plan's spread, as the planner computed it
            assert not driver.find_element(By.ID, "ensemble-panel").get_attribute(
                "class").count("hidden")
            fuel = [td.text for td in driver.find_elements(By.CSS_SELECTOR, "#ens-fuel td")]
            assert fuel == [f"{v:.1f}" for v in plan.fuel_quantiles_t]
            assert _text(driver, "ens-p-hs") == f"{100 * plan.p_hs_violation:.0f} %"
            assert f"{plan.ensemble_members} members" in _text(driver, "ens-ident")
            assert weather.running and display.running
        finally:
            driver.quit()
            node.destroy_node()
