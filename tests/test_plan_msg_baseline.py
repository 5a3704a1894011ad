"""The baseline's feasibility travels in `RoutePlan.baseline_feasible` (library plan ->
message) and the demo's plan line reads it there: a saving against a baseline the ship
could not sail is marked, one against a feasible baseline is not."""

from __future__ import annotations

import dataclasses

import pytest


@pytest.mark.parametrize("baseline_feasible", [True, False])
def test_baseline_feasibility_reaches_the_message_and_the_demo_line(baseline_feasible):
    pytest.importorskip("shiproute_msgs.msg")
    from shiproute_bringup.demo import _line
    from shiproute_display.samples import load_sample_plan
    from shiproute_planner.ros.convert import plan_to_msg, time_msg

    plan = dataclasses.replace(load_sample_plan("plan_cycle1"),
                               baseline_feasible=baseline_feasible, warnings=())
    msg = plan_to_msg(plan, time_msg(plan.departure_s))
    assert msg.baseline_feasible is baseline_feasible
    line = _line(msg, 0.0)
    assert ("vs constant RPM (infeasible)" in line) is (not baseline_feasible)
