"""Bad input thrown at running nodes (issue 16): they stay up, answer, and keep the last good plan.

One node set for the whole module (weather node serving the calm June scenario, planner with a
short budget); this process is the integrator. Each case sends something bad - forecast cycles
(zero grid, NaN/zero spacing, huge declared size, infinite values, a stale model run, a partial
cycle, a dead publisher's half cycle), ship states (NaN, out of range, 1970, future), voyages
(unknown port, RTA before departure, unknown ship, destination on land, NaN), parameters,
a failing plan - and then checks the answer, the diagnostics' counts and that a good PlanRoute
request still yields a correct plan on the good cycle.
"""

from __future__ import annotations

import math
import time
from typing import Any

import pytest
from ros_nodes import weather_and_planner

pytestmark = [pytest.mark.ros]

RTA = "2026-06-16T18:00:00Z"
RTA_S = 1781632800.0
DEPART_S = 1780509600.0  # 2026-06-03T18:00:00Z
BUSAN = (35.08, 129.112)
LONG_BEACH = (33.74, -118.22)
BUDGET_S = 0.5
FLAG_RTA = 2
RPM_MAX = 104.0  # container_4600teu.yaml, engine.rpm_max


class Peer:
    """The integrator: publishers of every input, clients of every service, plan listener."""

    def __init__(self, ctx: Any) -> None:
        from diagnostic_msgs.msg import DiagnosticArray
        from rcl_interfaces.srv import GetParameters, SetParameters
        from rclpy.action import ActionClient
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.node import Node
        from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy

        from shiproute_msgs.action import PlanRoute
        from shiproute_msgs.msg import ForecastCycle, ForecastSlice, RoutePlan, ShipState
        from shiproute_msgs.srv import LoadForecast, SetVoyage

        self.node = Node("bad_input_peer", context=ctx)
        self.ex = SingleThreadedExecutor(context=ctx)
        self.ex.add_node(self.node)
        latched = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE,
                             durability=DurabilityPolicy.TRANSIENT_LOCAL)
        self.plans: list[Any] = []
        self.cycles: list[Any] = []
        self.diag: dict[str, dict[str, str]] = {}
        self.node.create_subscription(RoutePlan, "/shiproute/plan/route", self.plans.append,
                                      latched)
        self.node.create_subscription(ForecastCycle, "/shiproute/forecast/cycle",
                                      self.cycles.append, latched)
        self.node.create_subscription(DiagnosticArray, "/diagnostics", self._on_diag, 10)
        self.state_pub = self.node.create_publisher(ShipState, "/shiproute/ship_state", 10)
        self.cycle_pub = self.node.create_publisher(ForecastCycle, "/shiproute/forecast/cycle",
                                                    latched)
        slices_qos = QoSProfile(depth=512, reliability=ReliabilityPolicy.RELIABLE,
                                durability=DurabilityPolicy.TRANSIENT_LOCAL)
        self.slice_pub = self.node.create_publisher(ForecastSlice, "/shiproute/forecast/slices",
                                                    slices_qos)
        self.voyage = self.node.create_client(SetVoyage, "/shiproute/planner/set_voyage")
        self.load = self.node.create_client(LoadForecast, "/shiproute/forecast/load")
        self.set_params = self.node.create_client(SetParameters,
                                                  "/shiproute_planner/set_parameters")
        self.get_params = self.node.create_client(GetParameters,
                                                  "/shiproute_planner/get_parameters")
        self.action = ActionClient(self.node, PlanRoute, "/shiproute/planner/plan")
        self.types = {"ShipState": ShipState, "ForecastCycle": ForecastCycle,
                      "ForecastSlice": ForecastSlice, "SetVoyage": SetVoyage,
                      "PlanRoute": PlanRoute, "LoadForecast": LoadForecast,
                      "SetParameters": SetParameters, "GetParameters": GetParameters}
        self.state = (BUSAN[0], BUSAN[1], DEPART_S)

    def _on_diag(self, msg: Any) -> None:
        for status in msg.status:
            self.diag[status.name] = {kv.key: kv.value for kv in status.values}

    def planner_diag(self) -> dict[str, str]:
        return self.diag.get("shiproute_planner", {})

    def send_state(self, lat: float, lon: float, t_s: float, **extra: float) -> None:
        msg = self.types["ShipState"]()
        msg.header.stamp.sec = math.floor(t_s) if math.isfinite(t_s) else 0
        msg.latitude_deg, msg.longitude_deg = lat, lon
        msg.sog_kn, msg.cog_deg, msg.heading_deg = 17.0, 60.0, 60.0
        for k, v in extra.items():
            setattr(msg, k, v)
        self.state_pub.publish(msg)

    def spin_for(self, seconds: float) -> None:
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            self.ex.spin_once(timeout_sec=0.05)

    def spin_until(self, predicate: Any, timeout_s: float, what: str) -> Any:
        deadline = time.monotonic() + timeout_s
        next_state = 0.0
        while time.monotonic() < deadline:
            if time.monotonic() >= next_state:
                self.send_state(*self.state)
                next_state = time.monotonic() + 0.5
            self.ex.spin_once(timeout_sec=0.05)
            value = predicate()
            if value:
                return value
        raise AssertionError(f"{what} not within {timeout_s:.0f} s")

    def call(self, client: Any, request: Any, timeout_s: float = 30.0) -> Any:
        assert client.wait_for_service(timeout_sec=20.0), f"{client.srv_name} not available"
        future = client.call_async(request)
        return self.spin_until(lambda: future.done() and future, timeout_s,
                               f"answer of {client.srv_name}").result()

    def plan_goal(self, budget_s: float = BUDGET_S, timeout_s: float = 60.0) -> tuple[Any, float]:
        """Send a PlanRoute goal; its result and how long it took [s]."""
        assert self.action.wait_for_server(timeout_sec=20.0)
        goal = self.types["PlanRoute"].Goal(reason="test request", budget_s=budget_s)
        t0 = time.monotonic()
        sent = self.action.send_goal_async(goal)
        handle = self.spin_until(lambda: sent.done() and sent.result(), 20, "goal accepted")
        done = handle.get_result_async()
        result = self.spin_until(lambda: done.done() and done.result(), timeout_s, "goal result")
        return result.result, time.monotonic() - t0

    def set_voyage(self, **kw: Any) -> Any:
        req = self.types["SetVoyage"].Request()
        for k, v in kw.items():
            if k == "rta_s":
                req.rta.sec = int(v)
            else:
                setattr(req, k, v)
        return self.call(self.voyage, req)

    def close(self) -> None:
        self.action.destroy()
        self.ex.shutdown()
        self.node.destroy_node()


def _good_plan_check(peer: Peer, good_cycle: str) -> Any:
    """A PlanRoute goal succeeds with a correct plan on the good cycle: Busan -> Long Beach,
    departing at the ship's last good fix, fuel = sum of the legs, within the RTA, feasible."""
    result, _ = peer.plan_goal()
    assert result.success, result.message
    plan = peer.spin_until(
        lambda: next((p for p in peer.plans if p.plan_id == result.plan_id), None), 20,
        "the goal's plan")
    assert plan.cycle_id == good_cycle
    w0, wn = plan.waypoints[0], plan.waypoints[-1]
    assert abs(w0.latitude_deg - BUSAN[0]) < 0.3 and abs(w0.longitude_deg - BUSAN[1]) < 0.3
    assert abs(wn.latitude_deg - LONG_BEACH[0]) < 0.3
    assert abs(((wn.longitude_deg - LONG_BEACH[1]) + 180) % 360 - 180) < 0.3
    assert abs(plan.departure_time.sec - DEPART_S) < 1.0
    fuel = sum(w.leg_fuel_t for w in plan.waypoints[:-1])
    assert math.isclose(fuel, plan.total_fuel_t, rel_tol=1e-9)
    assert plan.feasible, list(plan.infeasible_reasons)
    assert plan.eta.sec <= RTA_S + 1
    # a 4,600 TEU ship over ~5,000 NM in 13 days: 17.7 kn / 55.5 t/day at 77 rpm in calm water
    # (ship README); slower steaming in calm June needs less: between 250 and 900 t
    assert 250.0 < plan.total_fuel_t < 900.0
    return plan


# ---------------------------------------------------------------- bad forecast messages
def _field(name: str, values: list[float], ftype: Any) -> Any:
    import array

    f = ftype()
    f.name, f.units = name, "m" if "height" in name else "m s-1"
    f.data = array.array("f", values)
    return f


def _slice(peer: Peer, cycle_id: str, index: int, count: int, *, ref_s: float, valid_s: float,
           grid: tuple[float, float, int, float, float, int], publication: str = "",
           values: float = 1.0) -> Any:
    from shiproute_msgs.msg import ForecastField

    lat0, dlat, n_lat, lon0, dlon, n_lon = grid
    msg = peer.types["ForecastSlice"]()
    msg.cycle_id, msg.slice_index, msg.slice_count = cycle_id, index, count
    msg.reference_time.sec, msg.valid_time.sec = int(ref_s), int(valid_s)
    msg.lat0_deg, msg.dlat_deg, msg.n_lat = lat0, dlat, n_lat
    msg.lon0_deg, msg.dlon_deg, msg.n_lon = lon0, dlon, n_lon
    msg.publication_id = publication
    n = min(max(n_lat * n_lon, 0), 10_000)  # a huge declaration carries little data
    msg.fields = [_field(name, [values] * n, ForecastField) for name in (
        "eastward_wind", "northward_wind", "sea_surface_wave_significant_height")]
    return msg


def _announce(peer: Peer, cycle_id: str, count: int, ref_s: float, publication: str = "") -> None:
    msg = peer.types["ForecastCycle"]()
    msg.cycle_id, msg.slice_count, msg.publication_id = cycle_id, count, publication
    msg.reference_time.sec = int(ref_s)
    peer.cycle_pub.publish(msg)


PACIFIC = (10.0, 5.0, 11, 115.0, 5.0, 27)  # 10..60 N, 115..245 E every 5 deg


@pytest.fixture(scope="module")
def nodes(tmp_path_factory: pytest.TempPathFactory):
    with weather_and_planner(tmp_path_factory.mktemp("bad_input"), RTA, BUDGET_S) as (
            ctx, weather, planner, forecast):
        peer = Peer(ctx)
        try:
            peer.spin_until(lambda: peer.plans, 120, "first plan")
            good = peer.plans[-1].cycle_id
            ref_s = next(c for c in peer.cycles if c.cycle_id == good).reference_time.sec
            yield peer, good, float(ref_s), forecast, weather, planner
        finally:
            peer.close()


def _settle_state(peer: Peer) -> None:
    """Send the peer's ship state a few times so the planner holds it before what follows."""
    for _ in range(6):
        peer.send_state(*peer.state)
        peer.spin_for(0.2)


def _assert_alive(*procs: Any) -> None:
    for p in procs:
        assert p.running, f"{p.name} died:\n{p.output[-3000:]}"


@pytest.mark.parametrize("case", ["zero_grid", "nan_spacing", "zero_dlon", "huge_grid",
                                  "infinite_values", "stale_reference", "partial",
                                  "dead_publisher_half"])
def test_bad_cycle_refused_and_good_plan_follows(nodes: Any, case: str) -> None:
    peer, good, ref_s, _forecast, weather, planner = nodes
    t0 = DEPART_S - 6 * 3600
    cid = f"bad-{case}-{time.monotonic_ns()}"
    before = dict(peer.planner_diag())
    if case == "zero_grid":
        _announce(peer, cid, 1, ref_s)
        peer.slice_pub.publish(_slice(peer, cid, 0, 1, ref_s=ref_s, valid_s=t0,
                                      grid=(10.0, 0.5, 0, 115.0, 0.5, 0)))
    elif case in ("nan_spacing", "zero_dlon"):
        grid = (10.0, math.nan, 11, 115.0, 5.0, 27) if case == "nan_spacing" else \
            (10.0, 5.0, 11, 115.0, 0.0, 27)
        _announce(peer, cid, 1, ref_s)
        peer.slice_pub.publish(_slice(peer, cid, 0, 1, ref_s=ref_s, valid_s=t0, grid=grid))
    elif case == "huge_grid":
        _announce(peer, cid, 2, ref_s)
        peer.slice_pub.publish(_slice(peer, cid, 0, 2, ref_s=ref_s, valid_s=t0,
                                      grid=(-90.0, 1e-6, 1_000_000, 0.0, 1e-6, 1_000_000)))
    elif case == "infinite_values":
        _announce(peer, cid, 1, ref_s)
        peer.slice_pub.publish(_slice(peer, cid, 0, 1, ref_s=ref_s, valid_s=t0, grid=PACIFIC,
                                      values=math.inf))
    elif case == "stale_reference":  # well formed, but a model run a day older than in force
        old = ref_s - 86400.0
        _announce(peer, cid, 2, old)
        for k in range(2):
            peer.slice_pub.publish(_slice(peer, cid, k, 2, ref_s=old, valid_s=t0 + k * 86400 * 14,
                                          grid=PACIFIC))
    elif case == "partial":  # announced 3, one slice sent: never used
        _announce(peer, cid, 3, ref_s + 3600)
        peer.slice_pub.publish(_slice(peer, cid, 0, 3, ref_s=ref_s + 3600, valid_s=t0,
                                      grid=PACIFIC))
    elif case == "dead_publisher_half":  # a killed publisher's half, a restarted one's half
        newer = ref_s + 3600
        _announce(peer, cid, 2, newer, publication="dead-1")
        peer.slice_pub.publish(_slice(peer, cid, 0, 2, ref_s=newer, valid_s=t0, grid=PACIFIC,
                                      publication="dead-1"))
        _announce(peer, cid, 2, newer, publication="alive-1")
        peer.slice_pub.publish(_slice(peer, cid, 1, 2, ref_s=newer, valid_s=t0 + 14 * 86400,
                                      grid=PACIFIC, publication="alive-1"))
    peer.spin_for(1.5)
    _assert_alive(weather, planner)
    assert all(p.cycle_id != cid for p in peer.plans)
    n0 = int(before.get("forecast_cycles_dropped", "0"))
    refused = case not in ("partial", "dead_publisher_half")

    def settled() -> dict[str, str] | None:
        d = peer.planner_diag()
        if d.get("forecast_cycle_in_force") != good:
            return None
        if refused and not (int(d.get("forecast_cycles_dropped", "0")) > n0
                            and cid in d.get("forecast_last_refusal", "")):
            return None
        return d

    diag = peer.spin_until(settled, 20, "diagnostics naming the refused cycle")
    assert diag["forecast_cycle_in_force"] == good
    plan = _good_plan_check(peer, good)
    assert plan.cycle_id == good


def test_reloading_the_same_file_plans_again(nodes: Any) -> None:
    peer, good, _ref, forecast, weather, planner = nodes
    for _ in range(1):  # loaded at start, then again: same file, same cycle id
        n = len(peer.plans)
        ans = peer.call(peer.load, peer.types["LoadForecast"].Request(paths=[str(forecast)]),
                        timeout_s=60)
        assert ans.accepted, ans.message
        assert ans.cycle_id == good
        peer.spin_until(lambda n=n: len(peer.plans) > n and peer.plans[-1].cycle_id == good,
                        60, "plan on the reloaded cycle")
    _assert_alive(weather, planner)


@pytest.mark.parametrize("case", ["nan_lat", "lat_91", "inf_lon", "stamp_1970", "future",
                                  "inf_sog"])
def test_bad_ship_state_dropped_counted(nodes: Any, case: str) -> None:
    peer, good, _ref, _f, weather, planner = nodes
    n0 = int(peer.planner_diag().get("ship_states_dropped", "0"))
    bad = {"nan_lat": ((math.nan, 129.0, DEPART_S), {}),
           "lat_91": ((91.0, 129.0, DEPART_S), {}),
           "inf_lon": ((35.0, math.inf, DEPART_S), {}),
           "stamp_1970": ((35.5, 130.0, 0.0), {}),
           "future": ((35.5, 130.0, time.time() + 30 * 86400), {}),
           "inf_sog": ((35.5, 130.0, DEPART_S), {"sog_kn": math.inf})}[case]
    for _ in range(3):
        peer.send_state(*bad[0], **bad[1])
    diag = peer.spin_until(lambda: int(peer.planner_diag().get("ship_states_dropped", "0"))
                           >= n0 + 3 and peer.planner_diag(), 10, "drop count")
    assert diag["ship_states_last_reason"].startswith("ship state")
    _assert_alive(weather, planner)
    _good_plan_check(peer, good)


def _ship_with_missing_model(work: Any) -> str:
    """The bundled 4,600 TEU ship file naming a learned model file that is not there."""
    from pathlib import Path

    import shiproute_planner.ships as ships

    text = (Path(ships.__file__).parent / "container_4600teu.yaml").read_text()
    path = work / "ship_missing_model.yaml"
    path.write_text(text + "\nperformance_model: learned:missing_model.nc\n")
    return str(path)


@pytest.mark.parametrize("case", ["unknown_port", "rta_before_departure", "unknown_ship",
                                  "on_land", "nan_position", "bad_objective", "missing_model"])
def test_bad_voyage_refused_with_reason(nodes: Any, case: str) -> None:
    peer, good, _ref, forecast, weather, planner = nodes
    kw = {"unknown_port": {"destination": "Atlantis"},
          "rta_before_departure": {"destination": "Long Beach", "rta_s": DEPART_S - 86400},
          "unknown_ship": {"destination": "Long Beach", "ship": "flying_dutchman"},
          "on_land": {"destination": "", "destination_lat_deg": 39.0,
                      "destination_lon_deg": -100.0},
          "nan_position": {"destination": "", "destination_lat_deg": math.nan,
                           "destination_lon_deg": -118.0},
          "bad_objective": {"destination": "Long Beach", "objective": "speed"},
          "missing_model": {"destination": "Long Beach",
                            "ship": _ship_with_missing_model(forecast.parent)}}[case]
    ans = peer.set_voyage(**kw)
    assert not ans.accepted
    word = {"unknown_port": "Atlantis", "rta_before_departure": "RTA",
            "unknown_ship": "flying_dutchman", "on_land": "land", "nan_position": "latitude",
            "bad_objective": "objective", "missing_model": "missing_model.nc"}[case]
    assert word.lower() in ans.message.lower(), ans.message
    assert not ans.message.startswith(("ModelFileError(", "UnknownShipError(")), ans.message
    _assert_alive(weather, planner)
    _good_plan_check(peer, good)


def test_impossible_rta_gives_flagged_best_effort_plan(nodes: Any) -> None:
    peer, good, _ref, _f, weather, planner = nodes
    n = len(peer.plans)
    ans = peer.set_voyage(destination="Long Beach", rta_s=DEPART_S + 3600)
    assert ans.accepted, ans.message
    assert "unreachable" in ans.message
    plan = peer.spin_until(lambda: len(peer.plans) > n and peer.plans[-1], 60, "best effort")
    assert not plan.feasible
    assert any(w.constraint_flags & FLAG_RTA for w in plan.waypoints) or any(
        "RTA" in r for r in plan.infeasible_reasons)
    assert any("RTA unreachable" in w for w in plan.warnings), list(plan.warnings)
    # best effort: the engine at its maximum (104 rpm in the ship file) over the ocean
    assert max(w.shaft_rpm for w in plan.waypoints[:-1]) >= 0.95 * RPM_MAX
    ans = peer.set_voyage(destination="Long Beach", rta_s=RTA_S)
    assert ans.accepted, ans.message
    _assert_alive(weather, planner)
    _good_plan_check(peer, good)


def test_set_voyage_port_calls(nodes: Any) -> None:
    """SetVoyage with port calls: a malformed call is refused naming it; a good one plans a
    multi-port voyage that reports each call's arrival and departure (berth included)."""
    from shiproute_msgs.msg import PortCall

    peer, good, _ref, _f, weather, planner = nodes
    bad = PortCall(port="Yokohama", berth_hours=12.0)
    bad.latest_arrival.sec = int(DEPART_S - 86400)
    ans = peer.set_voyage(destination="Long Beach", rta_s=RTA_S, port_calls=[bad])
    assert not ans.accepted and "Yokohama" in ans.message, ans.message
    n = len(peer.plans)
    call = PortCall(port="Yokohama", berth_hours=12.0)
    ans = peer.set_voyage(destination="Long Beach", rta_s=RTA_S, port_calls=[call])
    assert ans.accepted, ans.message
    plan = peer.spin_until(lambda: len(peer.plans) > n and peer.plans[-1], 90, "multi-port")
    assert list(plan.call_ports) == ["Yokohama", "Long Beach"]
    stay_s = plan.call_departures[0].sec - plan.call_arrivals[0].sec
    assert stay_s >= 12 * 3600 - 1
    ans = peer.set_voyage(destination="Long Beach", rta_s=RTA_S)  # direct again
    assert ans.accepted, ans.message
    _assert_alive(weather, planner)
    _good_plan_check(peer, good)


def test_parameters_and_goal_budget(nodes: Any) -> None:
    from rcl_interfaces.msg import Parameter, ParameterType, ParameterValue

    peer, _good, _ref, _f, _weather, _planner = nodes
    req = peer.types["SetParameters"].Request(parameters=[Parameter(
        name="stage_hours", value=ParameterValue(type=ParameterType.PARAMETER_DOUBLE,
                                                 double_value=1000.0))])
    res = peer.call(peer.set_params, req)
    assert not res.results[0].successful
    assert "stage_hours" in res.results[0].reason
    result, _ = peer.plan_goal(budget_s=0.3)
    assert result.success, result.message
    got = peer.call(peer.get_params, peer.types["GetParameters"].Request(
        names=["budget_s", "stage_hours"]))
    assert got.values[0].double_value == BUDGET_S  # the goal's budget was its own
    assert got.values[1].double_value == 0.0  # the default: derived from the voyage


def test_goal_aborts_as_soon_as_planning_fails(nodes: Any) -> None:
    peer, good, _ref, _f, weather, planner = nodes
    peer.state = (36.2, 138.2, DEPART_S + 600)  # valid fix, but in the Japanese Alps
    _settle_state(peer)
    try:
        n0 = int(peer.planner_diag().get("plan_requests_dropped", "0"))
        # a minute of budget: a goal that waited for its budget instead of the failure would
        # take 60 s; planning fails in well under a second and the goal ends with it
        result, took = peer.plan_goal(budget_s=60.0, timeout_s=120.0)
        assert not result.success
        assert "land" in result.message, result.message
        assert took < 10.0
        diag = peer.spin_until(
            lambda: int(peer.planner_diag().get("plan_requests_dropped", "0")) > n0
            and peer.planner_diag(), 10, "the failed goal counted")
        assert "land" in diag["plan_requests_last_reason"]
    finally:
        peer.state = (BUSAN[0], BUSAN[1], DEPART_S)
        _settle_state(peer)
    _assert_alive(weather, planner)
    _good_plan_check(peer, good)


def test_counts_reach_diagnostics(nodes: Any) -> None:
    peer, good, _ref, forecast, weather, planner = nodes
    diag = peer.spin_until(lambda: peer.planner_diag(), 5, "diagnostics")
    for kind in ("ship_states", "forecast_slices", "forecast_cycles", "voyage_requests",
                 "plan_requests"):
        assert f"{kind}_dropped" in diag and f"{kind}_last_reason" in diag
    # a refused goal (budget outside 0.05..3600 s) is counted with its reason
    n0 = int(diag["plan_requests_dropped"])
    result, _ = peer.plan_goal(budget_s=1e5)
    assert not result.success and "budget_s" in result.message
    diag = peer.spin_until(lambda: int(peer.planner_diag()["plan_requests_dropped"]) > n0
                           and peer.planner_diag(), 10, "refused goal counted")
    assert "budget_s" in diag["plan_requests_last_reason"]
    # a refused forecast load is counted by the weather node, the cycle in force named
    name = "shiproute_weather: forecast"
    bad = forecast.parent / "not_a_forecast.nc"
    bad.write_text("this is not NetCDF")
    n0 = int(peer.diag.get(name, {}).get("loads_refused", "0"))
    ans = peer.call(peer.load, peer.types["LoadForecast"].Request(paths=[str(bad)]),
                    timeout_s=60)
    assert not ans.accepted and "not_a_forecast.nc" in ans.message
    wdiag = peer.spin_until(lambda: int(peer.diag.get(name, {}).get("loads_refused", "0"))
                            > n0 and peer.diag[name], 10, "weather refusal counted")
    assert "not_a_forecast.nc" in wdiag["loads_refused_last_reason"]
    assert wdiag["cycle_id"] == good
    _assert_alive(weather, planner)

