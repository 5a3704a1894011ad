"""The planner node's PlanRoute action: one goal asks for a plan (or a time-fuel front) with
its own budget and objective, and ends as soon as the run that answers it ends."""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from builtin_interfaces.msg import Time
from rclpy.action.server import ServerGoalHandle

from shiproute_msgs.action import PlanRoute

from ..checks.parameters import check_number
from ..plan_types import RoutePlan
from .convert import plan_feedback, plan_messages
from .drop_log import DropLog
from .parameters import goal_objective_reason
from .plan_worker import PlanWorker


@dataclass(frozen=True)
class GoalDesk:
    """What a PlanRoute goal needs of the planner node: its plan worker and drop log, and
    read-only views of its state (the node owns one and hands it to every goal)."""

    worker: PlanWorker
    drops: DropLog
    default_budget_s: Callable[[], float]  # the budget_s parameter now
    # (reason, budget_s or None, objective, front points) -> the request's number
    request: Callable[[str, float | None, str, int], int]
    front: Callable[[], tuple[int, tuple[RoutePlan, ...]]]  # (request, plans) of the last front
    progress: Callable[[], dict[str, float]]  # the running plan's progress values
    last_error: Callable[[], str]
    stamp: Callable[[], Time]  # the node's clock now, as a message stamp


def run_goal(desk: GoalDesk, goal_handle: ServerGoalHandle) -> Any:
    """Plan for this goal (with its own budget, the parameter untouched) and end as soon
    as the run that answers it ends: succeeded with the plan, or aborted with the reason."""
    result = PlanRoute.Result()
    budget = float(goal_handle.request.budget_s)
    reason = check_number("budget_s", budget) if budget != 0.0 else None
    if reason is not None:
        desk.drops.drop("plan_requests", reason)
        goal_handle.abort()
        result.message = f"goal refused: {reason}"
        return result
    objective = str(goal_handle.request.objective).strip()
    points = int(goal_handle.request.front_points) or 9
    reason = goal_objective_reason(objective, points)
    if reason is not None:
        desk.drops.drop("plan_requests", reason)
        goal_handle.abort()
        result.message = f"goal refused: {reason}"
        return result
    goal_budget = budget if budget > 0 else desk.default_budget_s()
    if objective == "front":
        goal_budget *= 1 if budget > 0 else points
    seq = desk.request(goal_handle.request.reason or "plan requested",
                       budget if budget > 0 else None, objective, points)
    start = time.monotonic()
    deadline = start + 10.0 * goal_budget + 60.0  # a stuck run (never seen) still ends
    while time.monotonic() < deadline:
        if goal_handle.is_cancel_requested:
            desk.worker.cancel.set()
            goal_handle.canceled()
            result.message = "cancelled"
            return result
        answered, ok, text = desk.worker.outcome()
        if answered >= seq:
            result.success, result.message = ok, "planned" if ok else text
            result.plan_id = text if ok else ""
            front_seq, plans = desk.front()
            if ok and objective == "front" and front_seq >= seq:
                stamp = desk.stamp()
                result.front = [plan_messages(p, stamp, "time-fuel front")[2] for p in plans]
                result.message = f"time-fuel front of {len(plans)} plans"
            if ok:
                goal_handle.succeed()
            else:
                desk.drops.drop("plan_requests", text)
                goal_handle.abort()
            return result
        goal_handle.publish_feedback(plan_feedback(desk.progress(), time.monotonic() - start))
        desk.worker.wait(0.2)
    goal_handle.abort()
    result.message = f"no answer within {deadline - start:.0f} s: {desk.last_error()}"
    return result
