"""Shared helpers of the display tests: the real sample plans as planner RoutePlans and messages."""

from __future__ import annotations

from typing import Any

from shiproute_display.samples import load_sample_plan


def load_plan(name: str) -> Any:
    """A sample plan (shiproute_display/sample_plans) as a planner RoutePlan."""
    return load_sample_plan(name)


def plan_messages(plan: Any, stamp_s: float, trigger: str = "") -> tuple[Any, Any]:
    """(RoutePlan msg, RpmProfile msg) exactly as the planner node makes them."""
    from shiproute_planner.ros.convert import plan_to_msg, plan_to_rpm_profile, time_msg

    msg = plan_to_msg(plan, time_msg(stamp_s))
    if trigger:
        msg.trigger = trigger
    return msg, plan_to_rpm_profile(plan, time_msg(stamp_s))
