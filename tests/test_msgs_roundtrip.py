"""Every shiproute_msgs type survives a trip through another process (fields, arrays, NaN).

The test process publishes fully populated messages; ``roundtrip_echo.py`` (a separate process
on a random domain) republishes them unchanged, and the copies received back must equal the
originals field by field (NaN == NaN, float32 arrays bit-exact, 16-bit packed fields with their
scale constants exact and decoding to the same values). Services and the action are
called across the same process boundary. Also checks the wrapper's usage errors and `env --json`.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from shiproute_bringup.msgdict import plain_equal, to_plain

REPO = Path(__file__).resolve().parents[1]
WRAPPER = REPO / "ros2_ws" / "shiproute"
ECHO = Path(__file__).with_name("roundtrip_echo.py")

MESSAGE_TYPES = ("ForecastField", "ForecastSlice", "ForecastCycle", "ShipState", "RpmStage",
                 "RpmProfile", "RouteWaypoint", "RoutePlan")


def _time(sec: int, nanosec: int = 0) -> Any:
    from builtin_interfaces.msg import Time

    return Time(sec=sec, nanosec=nanosec)


def _header(sec: int) -> Any:
    from std_msgs.msg import Header

    return Header(stamp=_time(sec, 123_456_789), frame_id="wgs84")


def _field(name: str, units: str, convention: str, n: int, seed: int) -> Any:
    from shiproute_msgs.msg import ForecastField

    data = np.random.default_rng(seed).normal(5.0, 3.0, n).astype(np.float32)
    data[::7] = np.nan  # missing values (land) must stay NaN, never 0
    data[1] = np.float32(-0.0)
    data[2] = np.finfo(np.float32).max
    data[3] = np.finfo(np.float32).tiny  # smallest normal float32
    return ForecastField(name=name, units=units, direction_convention=convention,
                         data=data.tolist())


def _packed_field(name: str, units: str, convention: str, n: int, seed: int) -> Any:
    """A field in 16-bit simple packing (ForecastField.msg): codes 0 (the minimum), 65534 (the
    maximum) and 65535 (missing) included; float32 `data` left empty."""
    from shiproute_weather.wire.packing import pack_field

    from shiproute_msgs.msg import ForecastField

    values = np.random.default_rng(seed).uniform(0.0, 360.0, n).astype(np.float32)
    values[::11] = np.nan
    packed = pack_field(values, name)
    assert {0, 65534, 65535} <= set(np.unique(packed.codes).tolist())
    return ForecastField(name=name, units=units, direction_convention=convention,
                         packed=packed.codes.tolist(), add_offset=packed.add_offset,
                         scale_factor=packed.scale_factor)


def _waypoint(i: int, last: bool) -> Any:
    from shiproute_msgs.msg import RoutePlan, RouteWaypoint

    leg = math.nan if last else 1.0
    return RouteWaypoint(
        latitude_deg=35.1 + 0.5 * i, longitude_deg=179.9 - 0.25 * i if i else -179.99,
        time=_time(1_772_524_800 + 3600 * i), heading_deg=leg * 87.5, shaft_rpm=leg * 78.25,
        stw_kn=leg * 14.1, sog_kn=leg * 13.7, leg_distance_nm=leg * 41.3,
        leg_duration_s=leg * 10_800.0, leg_fuel_t=leg * 4.2, brake_power_kw=leg * 11_250.0,
        hs_m=leg * 3.4, wave_from_deg=leg * 275.0, wind_speed_m_s=leg * 12.2,
        wind_from_deg=leg * 290.0, p_slamming=leg * 1e-4, p_deck_wetness=leg * 0.02,
        p_propeller_emergence=leg * 0.005,
        constraint_flags=0 if last else RoutePlan.FLAG_SLAMMING | RoutePlan.FLAG_ENGINE_LIMIT)


def build_messages() -> dict[str, Any]:
    """One fully populated instance of every message type (non-default in every field)."""
    import shiproute_msgs.msg as m

    n_lat, n_lon = 61, 121
    fields = [
        _field("eastward_wind", "m s-1", "", n_lat * n_lon, 1),
        _field("sea_surface_wave_from_direction", "degree", "coming_from", n_lat * n_lon, 2),
        _field("eastward_sea_water_velocity", "m s-1", "going_to", n_lat * n_lon, 3),
        _packed_field("sea_surface_swell_wave_from_direction", "degree", "coming_from",
                      n_lat * n_lon, 4),
    ]
    forecast_slice = m.ForecastSlice(
        header=_header(1_772_524_900), cycle_id="storm-2026030312",
        reference_time=_time(1_772_539_200), valid_time=_time(1_772_560_800), slice_index=3,
        slice_count=41, source="ECMWF-HRES+WAM", lat0_deg=20.0, lon0_deg=120.0, dlat_deg=0.5,
        dlon_deg=1.0, n_lat=n_lat, n_lon=n_lon, fields=fields)
    cycle = m.ForecastCycle(
        header=_header(1_772_524_901), cycle_id="storm-2026030312",
        reference_time=_time(1_772_539_200), first_valid_time=_time(1_772_539_200),
        last_valid_time=_time(1_772_539_200 + 40 * 10_800), step_s=10_800.0, slice_count=41,
        source="ECMWF-HRES+WAM", lat_min_deg=20.0, lat_max_deg=50.0, lon_min_deg=120.0,
        lon_max_deg=240.0, fields=[f.name for f in fields],
        source_files=["/data/a.grib2", "/data/b.nc", "ünïcödé ∆.nc"])
    ship = m.ShipState(
        header=_header(1_772_524_902), mmsi=4_294_967_295, latitude_deg=35.0812,
        longitude_deg=129.0756, sog_kn=14.25, cog_deg=78.5, heading_deg=80.1, stw_kn=math.nan,
        shaft_rpm=76.5, draft_fore_m=11.2, draft_aft_m=12.4, fuel_rate_t_per_h=math.inf,
        nav_status=m.ShipState.NAV_STATUS_UNDEFINED)
    stages = [m.RpmStage(start_time=_time(1_772_524_800 + 21_600 * i, 500), duration_s=21_600.0,
                         shaft_rpm=70.0 + i * 1.5, heading_deg=(45.0 * i) % 360.0)
              for i in range(40)]
    profile = m.RpmProfile(header=_header(1_772_524_903), plan_id="plan-0007", stages=stages)
    waypoints = [_waypoint(i, last=(i == 24)) for i in range(25)]
    route = m.RoutePlan(
        header=_header(1_772_524_904), plan_id="plan-0007", cycle_id="storm-2026030312",
        method="seed_ga", seed_source="previous_plan", objective="fuel", ship_name="pcc_6500",
        departure_time=_time(1_772_524_800), rta=_time(1_773_475_200, 1),
        eta=_time(1_773_460_000, 999_999_999), feasible=False,
        infeasible_reasons=["leg 3: slamming probability 0.031 > 0.03", "RTA missed by 0 s"],
        warnings=["depth not checked: no bathymetry given"],
        trigger="new forecast cycle storm-2026030312",
        total_fuel_t=812.75, total_distance_nm=5_120.4, total_time_s=935_200.0,
        baseline_fuel_t=math.nan, baseline_feasible=True, compute_time_s=0.842,
        waypoints=waypoints)
    return {"ForecastField": fields[3], "ForecastSlice": forecast_slice, "ForecastCycle": cycle,
            "ShipState": ship, "RpmStage": stages[5], "RpmProfile": profile,
            "RouteWaypoint": waypoints[0], "RoutePlan": route}


@pytest.fixture(scope="module")
def ros_peer() -> Any:
    """(executor, node, domain_id) of this process, with the echo process running."""
    pytest.importorskip("shiproute_msgs.msg")
    import rosproc
    from rclpy.executors import SingleThreadedExecutor
    from rclpy.node import Node

    dom = rosproc.random_domain_id()
    with rosproc.RosProcess([sys.executable, "-u", str(ECHO), *MESSAGE_TYPES], domain_id=dom,
                            name="roundtrip_echo") as echo, rosproc.ros_context(dom) as ctx:
        echo.wait_for_line(r"^READY$", timeout_s=20)
        node = Node("roundtrip_test", context=ctx)
        executor = SingleThreadedExecutor(context=ctx)
        executor.add_node(node)
        try:
            yield executor, node, dom
        finally:
            executor.shutdown()
            node.destroy_node()


@pytest.mark.ros
def test_every_message_type_round_trips_across_processes(ros_peer: Any) -> None:
    """All eight types come back equal; NaN, inf, -0.0 and float32 extremes preserved."""
    import rosproc
    from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy

    import shiproute_msgs.msg as m

    executor, node, _ = ros_peer
    qos = QoSProfile(depth=10, durability=DurabilityPolicy.TRANSIENT_LOCAL,
                     reliability=ReliabilityPolicy.RELIABLE)
    sent = build_messages()
    assert set(sent) == set(MESSAGE_TYPES)
    received: dict[str, Any] = {}
    pubs = {}
    for name in sent:
        cls = getattr(m, name)
        node.create_subscription(cls, f"/rt/out/{name}",
                                 lambda x, n=name: received.setdefault(n, x), qos)
        pubs[name] = node.create_publisher(cls, f"/rt/in/{name}", qos)
    rosproc.spin_until(executor, lambda: all(p.get_subscription_count() > 0
                                             for p in pubs.values()), 15, "echo subscriptions")
    for name, msg in sent.items():
        pubs[name].publish(msg)
    rosproc.spin_until(executor, lambda: len(received) == len(sent), 15,
                       f"echoed messages (got {sorted(received)})")

    for name, msg in sent.items():
        back = received[name]
        assert type(back) is type(msg)
        assert plain_equal(to_plain(msg), to_plain(back)), name
    # spot checks that the comparison itself is meaningful
    data_in = np.asarray(sent["ForecastSlice"].fields[0].data, dtype=np.float32)
    data_out = np.asarray(received["ForecastSlice"].fields[0].data, dtype=np.float32)
    assert data_out.shape == (61 * 121,)
    assert np.isnan(data_out[::7]).all() and np.isfinite(data_out[1:7]).all()
    assert np.array_equal(data_in.view(np.uint32), data_out.view(np.uint32))  # bit-exact, -0.0
    from shiproute_weather.ros.convert import field_values
    from shiproute_weather.wire.packing import unpack_field

    for packed_in, packed_out in ((sent["ForecastSlice"].fields[3],
                                   received["ForecastSlice"].fields[3]),
                                  (sent["ForecastField"], received["ForecastField"])):
        codes_out = np.asarray(packed_out.packed, dtype=np.uint16)
        assert codes_out.shape == (61 * 121,) and len(packed_out.data) == 0
        assert np.array_equal(np.asarray(packed_in.packed, dtype=np.uint16), codes_out)
        assert (packed_out.add_offset, packed_out.scale_factor) == (packed_in.add_offset,
                                                                    packed_in.scale_factor)
        assert np.array_equal(unpack_field(field_values(packed_out)),
                              unpack_field(field_values(packed_in)), equal_nan=True)
    assert math.isnan(received["ShipState"].stw_kn)
    assert math.isinf(received["ShipState"].fuel_rate_t_per_h)
    assert received["ShipState"].mmsi == 4_294_967_295
    assert received["ForecastCycle"].source_files[2] == "ünïcödé ∆.nc"
    assert math.isnan(received["RoutePlan"].waypoints[-1].leg_fuel_t)
    assert received["RoutePlan"].eta.nanosec == 999_999_999
    assert len(received["RpmProfile"].stages) == 40


def _call(executor: Any, node: Any, srv_type: Any, name: str, request: Any) -> Any:
    import rosproc

    client = node.create_client(srv_type, name)
    rosproc.spin_until(executor, client.service_is_ready, 15, f"service {name}")
    future = client.call_async(request)
    rosproc.spin_until(executor, future.done, 15, f"response of {name}")
    return future.result()


@pytest.mark.ros
def test_services_round_trip_across_processes(ros_peer: Any) -> None:
    """LoadForecast, Seek and SetVoyage requests arrive intact and responses come back."""
    from shiproute_msgs.srv import LoadForecast, Seek, SetVoyage

    executor, node, _ = ros_peer
    paths = ["/data/storm/a.grib2", "/data/storm/b.grib2"]
    res = _call(executor, node, LoadForecast, "/rt/srv/LoadForecast",
                LoadForecast.Request(paths=paths))
    assert (res.accepted, res.cycle_id, res.message) == (True, "|".join(paths), "2")
    res = _call(executor, node, LoadForecast, "/rt/srv/LoadForecast", LoadForecast.Request())
    assert (res.accepted, res.message) == (False, "0")

    res = _call(executor, node, Seek, "/rt/srv/Seek", Seek.Request(offset_s=3600.25))
    assert (res.success, res.message) == (True, "3600.25")
    res = _call(executor, node, Seek, "/rt/srv/Seek", Seek.Request(offset_s=math.nan))
    assert (res.success, res.message) == (False, "nan")

    req = SetVoyage.Request(destination="", destination_lat_deg=33.74,
                            destination_lon_deg=-118.27, ship="pcc_6500", objective="fuel")
    req.rta.sec, req.rta.nanosec = 1_773_475_200, 7
    res = _call(executor, node, SetVoyage, "/rt/srv/SetVoyage", req)
    assert res.accepted
    assert json.loads(res.message) == {
        "destination": "", "destination_lat_deg": 33.74, "destination_lon_deg": -118.27,
        "rta": [1_773_475_200, 7], "ship": "pcc_6500", "objective": "fuel"}


@pytest.mark.ros
def test_plan_route_action_round_trips_across_processes(ros_peer: Any) -> None:
    """Goal, feedback (NaN best fuel first) and result of PlanRoute cross the process boundary."""
    import rosproc
    from rclpy.action import ActionClient

    from shiproute_msgs.action import PlanRoute

    executor, node, _ = ros_peer
    client = ActionClient(node, PlanRoute, "/rt/plan")
    rosproc.spin_until(executor, client.server_is_ready, 15, "action server /rt/plan")
    feedback: list[Any] = []
    goal_future = client.send_goal_async(PlanRoute.Goal(reason="operator request", budget_s=2.5),
                                         feedback_callback=lambda f: feedback.append(f.feedback))
    rosproc.spin_until(executor, goal_future.done, 15, "goal acceptance")
    handle = goal_future.result()
    assert handle.accepted
    result_future = handle.get_result_async()
    rosproc.spin_until(executor, result_future.done, 15, "action result")
    result = result_future.result().result
    assert (result.success, result.plan_id, result.message) == (True, "operator request",
                                                                "budget 2.5")
    # feedback is best effort in ordering relative to the result; what arrived must be intact
    for fb in feedback:
        assert fb.generation in (1, 2) and fb.evaluations == 100 * fb.generation
        assert math.isnan(fb.best_fuel_t) if fb.generation == 1 else fb.best_fuel_t == 12.5


def _wrapper(*args: str, timeout_s: float = 120) -> subprocess.CompletedProcess[str]:
    return subprocess.run([str(WRAPPER), *args], capture_output=True, text=True,
                          timeout=timeout_s, check=False)


def test_wrapper_unknown_subcommand_is_a_usage_error() -> None:
    """`shiproute nosuchcmd` and bare `shiproute`: usage on stderr, exit code 2."""
    res = _wrapper("nosuchcmd")
    assert res.returncode == 2, res.stderr
    assert "unknown subcommand 'nosuchcmd'" in res.stderr and "usage:" in res.stderr
    assert "env" in res.stderr  # the listing names the real subcommands
    res = _wrapper()
    assert res.returncode == 2 and "missing subcommand" in res.stderr
    res = _wrapper("bench", "nosuchbench")
    assert res.returncode == 2 and "unknown benchmark 'nosuchbench'" in res.stderr
    res = _wrapper("env", "--no-such-option")
    assert res.returncode == 2 and "usage:" in res.stderr


def test_wrapper_env_json_reports_ros_and_messages() -> None:
    """`shiproute env --json` is one JSON object naming the RMW and importable msg packages."""
    res = _wrapper("env", "--json")
    assert res.returncode == 0, res.stderr
    report = json.loads(res.stdout)
    assert report["ros"]["rmw"]["identifier"] == "rmw_fastrtps_cpp"
    assert report["ros"]["automatic_discovery_range"] == "LOCALHOST"
    for pkg in ("std_msgs", "geometry_msgs", "nav_msgs", "sensor_msgs", "diagnostic_msgs",
                "rosgraph_msgs", "shiproute_msgs"):
        assert report["message_packages"][pkg]["importable"], pkg
    assert report["python"]["version"].startswith("3.")
