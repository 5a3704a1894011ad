"""The planner node's PlanRoute action: one goal asks for a plan (or a time-fuel front) with
its own budget and objective, and ends as soon as the run that answers it ends."""

from __future__ import annotations

import time
from typing import Any

from shiproute_msgs.action import PlanRoute

from ..checks.parameters import check_number
from .convert import plan_feedback, plan_messages
from .parameters import goal_objective_reason


def run_goal(node: Any, goal_handle: Any) -> Any:
    """Plan for this goal (with its own budget, the parameter untouched) and end as soon
    as the run that answers it ends: succeeded with the plan, or aborted with the reason."""
    result = PlanRoute.Result()
    budget = float(goal_handle.request.budget_s)
    reason = check_number("budget_s", budget) if budget != 0.0 else None
    if reason is not None:
        node._drops.drop("plan_requests", reason)
        goal_handle.abort()
        result.message = f"goal refused: {reason}"
        return result
    objective = str(goal_handle.request.objective).strip()
    points = int(goal_handle.request.front_points) or 9
    reason = goal_objective_reason(objective, points)
    if reason is not None:
        node._drops.drop("plan_requests", reason)
        goal_handle.abort()
        result.message = f"goal refused: {reason}"
        return result
    goal_budget = budget if budget > 0 else float(node._p("budget_s"))
    if objective == "front":
        goal_budget *= 1 if budget > 0 else points
    seq = node._request(goal_handle.request.reason or "plan requested",
                        budget if budget > 0 else None, objective, points)
    start = time.monotonic()
    deadline = start + 10.0 * goal_budget + 60.0  # a stuck run (never seen) still ends
    while time.monotonic() < deadline:
        if goal_handle.is_cancel_requested:
            node._worker.cancel.set()
            goal_handle.canceled()
            result.message = "cancelled"
            return result
        answered, ok, text = node._worker.outcome()
        if answered >= seq:
            result.success, result.message = ok, "planned" if ok else text
            result.plan_id = text if ok else ""
            front_seq, plans = node._front
            if ok and objective == "front" and front_seq >= seq:
                stamp = node.get_clock().now().to_msg()
                result.front = [plan_messages(p, stamp, "time-fuel front")[2] for p in plans]
                result.message = f"time-fuel front of {len(plans)} plans"
            if ok:
                goal_handle.succeed()
            else:
                node._drops.drop("plan_requests", text)
                goal_handle.abort()
            return result
        goal_handle.publish_feedback(plan_feedback(node._progress, time.monotonic() - start))
        node._worker.wait(0.2)
    goal_handle.abort()
    result.message = f"no answer within {deadline - start:.0f} s: {node._last_error}"
    return result

