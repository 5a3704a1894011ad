"""The planner node (a real process fed by the weather node) on request: a PlanRoute goal with
objective "front" returns the time-fuel front as RoutePlan[]; the ship model / loading
parameters are refused with the reason when they cannot be planned with."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import pytest
from ros_nodes import weather_and_planner
from test_bad_input_ros import BUDGET_S, RTA, Peer

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src/shiproute_planner/test/ship"))

pytestmark = [pytest.mark.ros]


@pytest.fixture(scope="module")
def peer(tmp_path_factory: pytest.TempPathFactory):
    work = tmp_path_factory.mktemp("front_goal")
    with weather_and_planner(work, RTA, BUDGET_S) as (ctx, _weather, planner, _forecast):
        p = Peer(ctx)
        try:
            p.spin_until(lambda: p.plans, 180, "first plan")
            yield p, planner, work
        finally:
            p.close()


def _goal(peer: Peer, objective: str, points: int, budget_s: float) -> Any:
    goal = peer.types["PlanRoute"].Goal(reason="front request", budget_s=budget_s,
                                        objective=objective, front_points=points)
    assert peer.action.wait_for_server(timeout_sec=20.0)
    sent = peer.action.send_goal_async(goal)
    handle = peer.spin_until(lambda: sent.done() and sent.result(), 20, "goal accepted")
    done = handle.get_result_async()
    return peer.spin_until(lambda: done.done() and done.result(), 240, "goal result").result


def test_front_goal_returns_a_monotone_front(peer: Any) -> None:
    p, planner, _ = peer
    in_force = p.plans[-1].plan_id
    result = _goal(p, "front", 3, 6.0)
    assert result.success, result.message
    front = list(result.front)
    assert len(front) >= 2, result.message
    eta = [m.eta.sec for m in front]
    fuel = [m.total_fuel_t for m in front]
    assert eta == sorted(eta) and fuel == sorted(fuel, reverse=True)
    assert front[0].feasible and front[-1].feasible
    assert p.plans[-1].plan_id == in_force  # the plan in force is not replaced by the front
    refused = _goal(p, "cheapest", 0, 1.0)
    assert not refused.success and "objective 'cheapest'" in refused.message
    assert planner.running


def test_model_and_loading_parameters_refused_with_reason(peer: Any) -> None:
    from rcl_interfaces.msg import Parameter, ParameterType, ParameterValue
    from shiproute_planner.ship import load_ship
    from test_ship_model_choice import _zero_model

    p, planner, work = peer
    other = _zero_model(load_ship("vlcc_270k"), Path(work) / "vlcc.nc")

    def set_string(name: str, value: str) -> Any:
        req = p.types["SetParameters"].Request(parameters=[Parameter(
            name=name, value=ParameterValue(type=ParameterType.PARAMETER_STRING,
                                            string_value=value))])
        return p.call(p.set_params, req).results[0]

    bad_model = set_string("ship_model", f"learned:{other}")
    assert not bad_model.successful and "not for 'container_4600teu'" in bad_model.reason
    bad_loading = set_string("loading", "25,25")
    assert not bad_loading.successful and "hull depth" in bad_loading.reason
    assert set_string("loading", "ballast").successful
    assert set_string("ship_model", "kwon").successful
    result, _ = p.plan_goal(budget_s=1.0, timeout_s=120.0)
    assert result.success, result.message
    assert planner.running
