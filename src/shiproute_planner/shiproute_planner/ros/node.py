"""Planner node: re-plans with the seed GA on every complete forecast cycle, on leaving the plan
and on request, and publishes the plan (Path, RpmProfile, RoutePlan) latched.

Threads: the executor (MultiThreadedExecutor) serves subscriptions, services, the action and
timers; planning runs on one worker thread, so the node stays responsive while it plans. A new
complete cycle while planning supersedes the running plan (it is cancelled and discarded).
Forecast slices are packed into the next cycle's sampler as they arrive, so a complete cycle
is ready to plan on at once and no other copy of it is kept.
"""

from __future__ import annotations

import math
import sys
import threading
import time

import rclpy
from diagnostic_msgs.msg import DiagnosticArray
from nav_msgs.msg import Path as PathMsg
from rcl_interfaces.msg import ParameterDescriptor, SetParametersResult
from rclpy.action import ActionServer, CancelResponse, GoalResponse
from rclpy.action.server import ServerGoalHandle
from rclpy.callback_groups import MutuallyExclusiveCallbackGroup, ReentrantCallbackGroup
from rclpy.node import Node

from shiproute_core import topics
from shiproute_msgs.action import PlanRoute
from shiproute_msgs.msg import ForecastCycle, ForecastSlice, RpmProfile, ShipState
from shiproute_msgs.msg import RoutePlan as RoutePlanMsg
from shiproute_msgs.srv import SetVoyage

from ..checks.ship_state import check_ship_state
from ..errors import PlannerError
from ..plan_types import RoutePlan
from ..ship.errors import ShipModelError
from ..voyage_params import check_parameter, parse_utc
from ..voyage_request import check_voyage_request
from . import process_tuning as tuning
from .convert import plan_messages, posix_s, ship_position, ship_state_optionals, voyage_request
from .cycle_ledger import CycleLedger
from .dds_profile import forget_profile, use_dynamic_slice_buffers
from .diagnostics import plan_log_line, planner_status, progress_values
from .drop_log import DropLog
from .forecast_intake import ForecastIntake
from .goal import GoalDesk, run_goal
from .memory_release import release_after_plan
from .parameters import DROP_KINDS, PARAMETERS, method_reason, paths
from .plan_call import front_from_parameters, plan_from_parameters, run_start, write_outputs
from .plan_worker import PlanInputs, PlanWorker
from .qos import ANNOUNCEMENTS, LATCHED, SLICES, STATE
from .replan_policy import ReplanThresholds, off_plan_reasons
from .spin import spin_with_intake
from .startup import load_depth_grids, seed_pool_statement, warm_up_logged


class PlannerNode(Node):
    """Thin ROS shell around `shiproute_planner.planning.plan`."""

    def __init__(self) -> None:
        super().__init__("shiproute_planner")
        for name, (default, text) in PARAMETERS.items():
            self.declare_parameter(name, default, ParameterDescriptor(description=text))
        self.add_on_set_parameters_callback(self._on_set_parameters)

        self._lock = threading.Lock()
        self._drops = DropLog(DROP_KINDS)
        self._forecast = None
        self._cycle_id = ""
        self._cycle_reference_s = 0.0  # reference time of the cycle in force (0: unknown)
        self._ledger = CycleLedger()  # planned, failed or superseded: every accepted cycle
        self._forecast_intake = ForecastIntake(
            self._drops, self.get_logger(),
            accept_older=lambda: bool(self._p("accept_older_forecasts")),
            ship_time_s=self._ship_time_s, in_force=self._in_force,
            take=self._take_cycle, report=self._report_error)
        # requests and their outcomes, so a PlanRoute goal waits for the run that answers it
        self._worker = PlanWorker(self._lock, self._snapshot, self._plan_once, self._plan_failed,
                                  lambda: warm_up_logged(self._p, self.get_logger()))
        self._plans_failed = 0
        self._ship: ShipState | None = None
        self._plan: RoutePlan | None = None
        self._front: tuple[int, tuple[RoutePlan, ...]] = (0, ())  # (request, plans) of a front
        self._plan_wall = 0.0
        self._last_replan_ship_s = -math.inf
        self._last_error = ""
        self._progress: dict[str, float] = {}
        self._plans_made = 0
        self._trim_memory = False
        self._goal_desk = GoalDesk(  # what a PlanRoute goal may see and ask of this node
            self._worker, self._drops, default_budget_s=lambda: float(self._p("budget_s")),
            request=self._request, front=lambda: self._front, progress=lambda: self._progress,
            last_error=lambda: self._last_error, stamp=lambda: self.get_clock().now().to_msg())

        io_group = ReentrantCallbackGroup()
        # the forecast arrives on a node of its own, spun by a single-threaded executor (see
        # `main`): packed in arrival order, ~2x faster per slice than through a thread pool
        self.intake = rclpy.create_node(
            f"{self.get_name()}_forecast_intake", namespace=self.get_namespace(),
            context=self.context, use_global_arguments=False)  # not renamed like this node
        self.intake.create_subscription(
            ForecastCycle, self.resolve_topic_name(topics.FORECAST_CYCLE),
            self._forecast_intake.on_cycle, ANNOUNCEMENTS)
        self.intake.create_subscription(
            ForecastSlice, self.resolve_topic_name(topics.FORECAST_SLICES),
            self._forecast_intake.on_slice, SLICES)
        self.create_subscription(ShipState, topics.SHIP_STATE, self._on_ship_state, STATE,
                                 callback_group=io_group)
        self._pub_path = self.create_publisher(PathMsg, topics.PLAN_PATH, LATCHED)
        self._pub_rpm = self.create_publisher(RpmProfile, topics.PLAN_RPM_PROFILE, LATCHED)
        self._pub_plan = self.create_publisher(RoutePlanMsg, topics.PLAN_ROUTE, LATCHED)
        self._pub_diag = self.create_publisher(DiagnosticArray, topics.DIAGNOSTICS, 10)
        self.create_service(SetVoyage, topics.PLANNER_SET_VOYAGE, self._on_set_voyage,
                            callback_group=io_group)
        self._action = ActionServer(
            self, PlanRoute, topics.PLANNER_PLAN_ACTION, self._execute_goal,
            goal_callback=lambda _g: GoalResponse.ACCEPT,
            cancel_callback=lambda _g: CancelResponse.ACCEPT,
            callback_group=ReentrantCallbackGroup(),
        )
        self.create_timer(1.0, self._tick, callback_group=MutuallyExclusiveCallbackGroup())
        self._log_seed_pool()
        self._load_bathymetry()
        self._worker.start()  # warms the planner up (startup.warm_planner) before planning
        self.get_logger().info("planner ready; waiting for a complete forecast cycle")

    def _load_bathymetry(self) -> None:
        """Read the depth grids now; a bad grid is reported here and by the plan that meets it."""
        try:
            self.get_logger().info(load_depth_grids(
                paths(str(self._p("bathymetry_files"))), bool(self._p("default_bathymetry"))))
        except PlannerError as err:
            self._report_error(f"bathymetry: {err}")

    def _log_seed_pool(self) -> None:
        """Say what the persisted seed pool holds, so a restart visibly continues from it."""
        directory = str(self._p("seed_pool_dir"))
        if not directory:
            return
        try:
            self.get_logger().info(seed_pool_statement(directory))
        except Exception as err:  # a damaged pool is reported; planning goes on without it
            self.get_logger().error(f"seed pool in {directory} unreadable: {err}")

    # ----------------------------------------------------------------- parameters
    def _p(self, name: str):
        return self.get_parameter(name).value

    def _on_set_parameters(self, params) -> SetParametersResult:
        for p in params:
            reason = check_parameter(p.name, p.value)
            if reason is None and p.name == "method":
                reason = method_reason(str(p.value))
            if reason is None and p.name in ("ship", "ship_model", "loading"):
                reason = self._ship_choice_reason(params)
            if reason is not None:
                self.get_logger().warning(f"rejected parameter: {reason}")
                return SetParametersResult(successful=False, reason=reason)
        return SetParametersResult(successful=True)

    def _ship_choice_reason(self, params) -> str | None:
        """Why the ship, loading condition and model after this change cannot be planned
        with (a model file of another ship, an unknown condition), or None."""
        from ..voyage_ship import model_choice_reason

        new = {p.name: p.value for p in params}
        return model_choice_reason(*(str(new.get(k, self._p(k)))
                                     for k in ("ship", "ship_model", "loading")))

    def _on_set_voyage(self, req: SetVoyage.Request, res: SetVoyage.Response):
        """Check the whole voyage first; answer accepted=false with the reason when it is
        invalid, accepted=true (with the RTA warning when it cannot be met) otherwise."""
        try:
            checked = check_voyage_request(
                voyage_request(req), origin=str(self._p("origin")), ship=str(self._p("ship")),
                objective=str(self._p("objective")), method=str(self._p("method")),
                rta=str(self._p("rta")), position=self._fix(),
                departure_time=str(self._p("departure_time")), clock_s=self._clock_s(),
                ship_model=str(self._p("ship_model")))
        except Exception as err:  # every refusal is an answer, never an exception
            known = PlannerError | ShipModelError | ValueError  # their messages name the input
            reason = str(err) if isinstance(err, known) else repr(err)
            self._drops.drop("voyage_requests", reason)
            self.get_logger().warning(f"voyage refused: {reason}")
            res.accepted, res.message = False, reason
            return res
        result = self.set_parameters_atomically(
            [rclpy.parameter.Parameter(k, value=v) for k, v in checked.parameters.items()])
        res.accepted = bool(result.successful)
        if not res.accepted:
            self._drops.drop("voyage_requests", result.reason)
            res.message = result.reason
            return res
        res.message = checked.message
        self.get_logger().info(f"voyage set: {checked.message}")
        self._request("voyage set")
        return res

    # ----------------------------------------------------------------- inputs
    def _in_force(self) -> tuple[str, float]:
        """Id and reference time of the forecast cycle in force ('' and 0 before one)."""
        return self._cycle_id, self._cycle_reference_s

    def _take_cycle(self, sampler, cycle_id: str, reference_s: float) -> None:
        """A complete cycle replaces the one in force and triggers a re-plan after the run in
        progress, which finishes on its own cycle (every good cycle gets its plan, within one
        budget of the next), and the freed slice buffers go back to the OS."""
        with self._lock:
            self._forecast, self._cycle_id = sampler, cycle_id
            self._cycle_reference_s = reference_s
            self._ledger.taken(cycle_id)
        self._request(f"new forecast cycle {cycle_id}")
        tuning.return_freed_memory(collect=False)  # the slice buffers: freed, not yet returned
        self._trim_memory = True

    def _report_error(self, text: str) -> None:
        self._last_error = text
        self.get_logger().error(text)

    def _ship_time_s(self) -> float:
        """Time of the last ship state (-inf before the first): older slices are not kept."""
        pos = ship_position(self._ship) if self._ship is not None else None
        return pos[2] if pos is not None else -math.inf

    def _clock_s(self) -> float:
        """The node's clock [POSIX s] (0 with simulated time before the first /clock)."""
        return self.get_clock().now().nanoseconds * 1e-9

    def _fix(self) -> tuple[float, float, float] | None:
        """(lat, lon, time) of the last accepted ship state, None before one."""
        return ship_position(self._ship) if self._ship is not None else None

    def _on_ship_state(self, msg: ShipState) -> None:
        """Checked before it is taken: a refused fix is counted with its reason and logged
        (throttled); the last good one stays."""
        try:
            check_ship_state(
                float(msg.latitude_deg), float(msg.longitude_deg), posix_s(msg.header.stamp),
                ship_state_optionals(msg), clock_s=self._clock_s(),
                max_age_s=float(self._p("ship_state_max_age_h")) * 3600.0,
                max_lead_s=float(self._p("ship_state_max_lead_h")) * 3600.0)
        except PlannerError as err:
            n = self._drops.drop("ship_states", str(err))
            self.get_logger().warning(f"ship state dropped ({n} so far): {err}",
                                      throttle_duration_sec=5.0)
            return
        first = self._ship is None
        self._ship = msg
        if first:
            self._request("first ship state")

    # ----------------------------------------------------------------- triggers
    def _request(self, reason: str, budget_s: float | None = None, objective: str = "",
                 front_points: int = 9) -> int:
        """Ask the worker for a plan (or a front); returns the request's number."""
        return self._worker.request(reason, budget_s, objective, front_points)

    def _tick(self) -> None:
        self._check_off_plan()
        self._publish_diagnostics()

    def _check_off_plan(self) -> None:
        plan, ship = self._plan, self._ship
        if plan is None or ship is None or self._worker.busy():
            return
        pos = ship_position(ship)
        if pos is None or pos[2] >= plan.eta_s:
            return
        if pos[2] - self._last_replan_ship_s < float(self._p("min_replan_interval_s")):
            return
        reasons = off_plan_reasons(plan, pos, ReplanThresholds(
            float(self._p("replan_cross_track_nm")), float(self._p("replan_schedule_h")) * 3600))
        if reasons:
            self._last_replan_ship_s = pos[2]
            self._request("off plan: " + "; ".join(reasons))

    # ----------------------------------------------------------------- planning
    def _snapshot(self, reason: str, budget_s: float | None, seq: int) -> PlanInputs | str:
        """What to plan on, or why nothing can be planned yet."""
        if self._forecast is None:
            return "no plan: no complete forecast cycle received yet"
        pos = self._fix()
        if pos is None and not self._p("plan_without_ship_state"):
            return "no plan: no valid ship state received yet"
        return PlanInputs(self._forecast, self._cycle_id, pos, self._plan, reason, budget_s, seq)

    def _plan_failed(self, inputs: PlanInputs, err: Exception) -> str:
        self._last_error = f"planning failed ({inputs.reason}): {err}"
        self._plans_failed += 1
        self._ledger.answered(inputs.cycle_id, planned=False)
        self.get_logger().error(self._last_error)
        return self._last_error

    def _plan_once(self, inputs: PlanInputs) -> str | None:
        """Plan and publish; the plan's id, None when the run was cancelled (goal, shutdown)."""
        origin = str(self._p("origin"))
        depart, position = run_start(
            origin, inputs.position, inputs.previous, str(self._p("departure_time")),
            float(self._p("departure_radius_nm")))
        self._progress = {}
        self.get_logger().info(f"planning ({inputs.reason}) on cycle {inputs.cycle_id}")
        if inputs.objective == "front":
            return self._plan_front(inputs)
        plan = plan_from_parameters(
            self._p, inputs.forecast, cycle_id=inputs.cycle_id, origin=origin, depart_s=depart,
            budget_s=inputs.budget_s if inputs.budget_s is not None
            else float(self._p("budget_s")), previous=inputs.previous, position=position,
            progress=self._on_progress, cancel=self._worker.cancel, objective=inputs.objective)
        if self._worker.cancel.is_set():
            self.get_logger().info(f"plan on {inputs.cycle_id} cancelled")
            return None
        self._publish(plan, inputs)
        # after publishing: files, then what a plan does not keep back to the OS
        self._write_outputs(plan, inputs.forecast)
        released = release_after_plan(collect=self._trim_memory)  # clean file pages, heap
        if self._trim_memory:
            self._trim_memory = False
            self.get_logger().info(released.text())
        return plan.plan_id

    def _plan_front(self, inputs: PlanInputs) -> str:
        """The time-fuel front, kept for the goal that asked; the plan in force stays."""
        n = inputs.front_points
        depart = (parse_utc(str(self._p("departure_time"))) if inputs.position is None
                  else inputs.position[2])
        front = front_from_parameters(
            self._p, inputs.forecast, cycle_id=inputs.cycle_id, depart_s=depart,
            position=inputs.position, points=n, cancel=self._worker.cancel,
            budget_s=(inputs.budget_s if inputs.budget_s is not None
                      else float(self._p("budget_s")) * n))
        self._front = (inputs.request_seq, front.plans)
        self.get_logger().info(
            f"time-fuel front: {len(front.plans)} plans, "
            + ", ".join(f"{(p.eta_s - depart) / 3600:.1f} h {p.total_fuel_t:.1f} t"
                        for p in front.plans) + f" in {front.compute_time_s:.1f} s")
        return front.plans[0].plan_id

    def _on_progress(self, progress) -> None:
        self._progress = progress_values(progress)

    def _publish(self, plan: RoutePlan, inputs: PlanInputs) -> None:
        path, rpm, plan_msg = plan_messages(plan, self.get_clock().now().to_msg(), inputs.reason)
        self._pub_path.publish(path)
        self._pub_rpm.publish(rpm)
        self._pub_plan.publish(plan_msg)
        self._plan, self._plan_wall = plan, time.monotonic()
        self._plans_made += 1
        self._ledger.answered(inputs.cycle_id, planned=True)
        self.get_logger().info(plan_log_line(plan, inputs.reason))

    def _write_outputs(self, plan: RoutePlan, sampler) -> None:
        out = str(self._p("output_dir"))
        if not out:
            return
        try:
            write_outputs(plan, sampler, out, bool(self._p("write_png")))
        except Exception as err:  # file output must not stop planning
            self._report_error(f"writing plan files to {out} failed: {err}")

    # ----------------------------------------------------------------- action
    def _execute_goal(self, goal_handle: ServerGoalHandle) -> PlanRoute.Result:
        """Plan for this goal (its own budget and objective; the parameters untouched)."""
        return run_goal(self._goal_desk, goal_handle)

    # ----------------------------------------------------------------- diagnostics
    def _publish_diagnostics(self) -> None:
        values = {
            "forecast_cycle": self._cycle_id or "none",
            "forecast_cycle_in_force": self._cycle_id or "none",
            "forecast_reference_time_s": f"{self._cycle_reference_s:.0f}",
            "forecast_last_refusal": self._forecast_intake.last_refusal or "none",
            "planning": str(self._worker.planning),
            "plans_made": str(self._plans_made),
            "plans_failed": str(self._plans_failed),
            "last_error": self._last_error,
            **self._drops.values(), **self._ledger.values(),
        }
        self._pub_diag.publish(planner_status(values, self._plan,
                                              time.monotonic() - self._plan_wall,
                                              self.get_clock().now().to_msg()))

    def shutdown(self) -> None:
        self._worker.stop()


def main(args: list[str] | None = None) -> int:
    """Console entry point `shiproute_planner_node [--ros-args ...]`."""
    tuning.return_large_blocks_at_once()
    tuning.hand_over_gil_often()
    profile = use_dynamic_slice_buffers(topics.FORECAST_SLICES)
    rclpy.init(args=sys.argv if args is None else args)
    node = PlannerNode()
    forget_profile(profile)
    spin_with_intake(node, node.intake)
    return 0


if __name__ == "__main__":
    sys.exit(main())
