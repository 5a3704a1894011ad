"""Planner node: re-plans with the seed GA on every complete forecast cycle, on leaving the plan
and on request, and publishes the plan (Path, RpmProfile, RoutePlan) latched.

Threads: the executor (MultiThreadedExecutor) serves subscriptions, services, the action and
timers; planning runs on one worker thread, so the node stays responsive while it plans. A new
complete cycle while planning supersedes the running plan (it is cancelled and discarded).
Forecast slices are packed into the next cycle's sampler as they arrive, so a complete cycle
is ready to plan on at once and no other copy of it is kept.
"""

from __future__ import annotations

import contextlib
import math
import sys
import threading
import time
from dataclasses import dataclass
from pathlib import Path

import rclpy
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue
from nav_msgs.msg import Path as PathMsg
from rcl_interfaces.msg import ParameterDescriptor, SetParametersResult
from rclpy.action import ActionServer, CancelResponse, GoalResponse
from rclpy.callback_groups import MutuallyExclusiveCallbackGroup, ReentrantCallbackGroup
from rclpy.executors import (
    ExternalShutdownException,
    MultiThreadedExecutor,
    SingleThreadedExecutor,
)
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

from shiproute_msgs.action import PlanRoute
from shiproute_msgs.msg import ForecastCycle, ForecastSlice, RpmProfile, ShipState
from shiproute_msgs.msg import RoutePlan as RoutePlanMsg
from shiproute_msgs.srv import SetVoyage

from .convert import (
    cycle_record,
    plan_to_msg,
    plan_to_path,
    plan_to_rpm_profile,
    posix_s,
    ship_position,
    slice_fields,
)
from .cycle_assembler import CycleAssembler
from .cycle_packer import CyclePacker, SliceFields, hs_field_at
from .dds_profile import forget_profile, use_dynamic_slice_buffers
from .plan_types import RoutePlan
from .replan_policy import ReplanThresholds, track_deviation
from .voyage_params import check_parameter, parse_utc

LATCHED = QoSProfile(
    depth=1,
    history=HistoryPolicy.KEEP_LAST,
    reliability=ReliabilityPolicy.RELIABLE,
    durability=DurabilityPolicy.TRANSIENT_LOCAL,
)
SLICES = QoSProfile(
    depth=512,
    history=HistoryPolicy.KEEP_LAST,
    reliability=ReliabilityPolicy.RELIABLE,
    durability=DurabilityPolicy.TRANSIENT_LOCAL,
)
STATE = QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE)
SLICES_TOPIC = "/shiproute/forecast/slices"
_ANNOUNCEMENT = -1  # the slice index `_feed` takes for a cycle announcement

PARAMETERS: dict[str, tuple[object, str]] = {
    "origin": ("Busan", "departure port (name, UN/LOCODE or 'lat,lon'); seed-pool key"),
    "destination": ("Long Beach", "arrival port (name, UN/LOCODE or 'lat,lon')"),
    "departure_time": ("", "ISO 8601 UTC departure when no ShipState has arrived"),
    "rta": ("2026-03-16T18:00:00Z", "required time of arrival, ISO 8601 UTC"),
    "ship": ("container_4600teu", "bundled ship name or ship file path"),
    "ship_model": ("", "physics | kwon | profile:FILE.nc | learned:FILE.nc; '' = the ship "
                   "file's performance_model, else physics"),
    "objective": ("fuel", "fuel | distance | eta"),
    "method": ("seed_ga", "route-finding method"),
    "stage_hours": (12.0, "fixed stage duration [h]"),
    "budget_s": (3.0, "wall-time budget of one plan [s]"),
    "rng_seed": (0, "seed of the GA's random generator"),
    "seed_pool_dir": ("", "seed pool directory (persists across restarts); '' = none"),
    "output_dir": ("", "directory for each plan's RTZ, GeoJSON, PNG and JSON; '' = none"),
    "write_png": (True, "also draw the PNG of each plan"),
    "replan_cross_track_nm": (20.0, "re-plan when the ship is this far off the track [NM]"),
    "replan_schedule_h": (3.0, "re-plan when this far ahead of/behind schedule [h]"),
    "min_replan_interval_s": (3600.0, "least ship-time between off-plan re-plans [s]"),
    "departure_radius_nm": (10.0, "within this of the origin the plan starts at the port [NM]"),
    "plan_without_ship_state": (False, "plan from origin/departure_time without a ShipState"),
    "bathymetry_files": ("", "bathymetry grids, comma-separated NetCDF paths (finest wins)"),
    "default_bathymetry": (True, "add the global ETOPO5 grid (Debian ferret-datasets)"),
    "ukc_margin_m": (1.0, "under-keel clearance margin on draft + squat + waves [m]"),
    "zones_files": ("", "no-go / avoid zone GeoJSON files, comma-separated"),
    "clearance_nm": (0.0, "distance from land the route check of each plan requires [NM]"),
    "approach_files": ("", "coastal passages from/to ports (RTZ/GeoJSON), comma-separated"),
}


def _paths(text: str) -> list[str]:
    """Comma-separated file list of a string parameter."""
    return [p.strip() for p in text.split(",") if p.strip()]


def _return_freed_memory(collect: bool = True) -> None:
    """Hand freed heap memory back to the OS: glibc keeps freed blocks otherwise, and a cycle
    leaves ~180 MB of freed slice buffers. malloc_trim runs without the GIL (ctypes), so it
    may overlap planning; the garbage collection (optional) does not."""
    import contextlib
    import ctypes
    import gc

    if collect:
        gc.collect()
    with contextlib.suppress(OSError, AttributeError):  # not glibc: nothing to do
        ctypes.CDLL("libc.so.6").malloc_trim(0)


def _freeze_long_lived() -> None:
    """Leave what the process holds now (modules, compiled kernels, coastline, tables: ~1e6
    objects) out of all later garbage collections: a full collection walked them in 45-95 ms
    with the GIL held, stalling slice intake and planning whenever one fell into a re-plan.
    Call it right after a full collection, so no garbage is kept (Python docs, `gc.freeze`);
    only the first call freezes."""
    import gc

    if gc.get_freeze_count() == 0:
        gc.freeze()


def _return_large_blocks_at_once() -> None:
    """Serve allocations from 512 KiB up (a packed slice's fields are 0.7 MB, float32 ones
    1.4 MB) by mmap, so their memory goes back to the OS when freed instead of piling up in
    the heap while a cycle streams in."""
    import ctypes

    m_mmap_threshold = -3  # glibc mallopt parameter
    with contextlib.suppress(OSError, AttributeError):
        ctypes.CDLL("libc.so.6").mallopt(m_mmap_threshold, 1 << 19)


def _memory_mb() -> tuple[float, float]:
    """Resident memory of this process and its high-water mark [MiB] (Linux; NaN elsewhere)."""
    values = {"VmRSS:": math.nan, "VmHWM:": math.nan}
    try:
        with open("/proc/self/status") as f:
            for line in f:
                key = line.split(":", 1)[0] + ":"
                if key in values:
                    values[key] = int(line.split()[1]) / 1024
    except (OSError, ValueError, IndexError):
        pass
    return values["VmRSS:"], values["VmHWM:"]


@dataclass
class _Inputs:
    """What one planning run works on (a consistent snapshot)."""

    forecast: object  # ForecastSampler of the cycle
    cycle_id: str
    position: tuple[float, float, float] | None
    previous: RoutePlan | None
    reason: str


class PlannerNode(Node):
    """Thin ROS shell around `shiproute_planner.planning.plan_voyage`."""

    def __init__(self) -> None:
        super().__init__("shiproute_planner")
        for name, (default, text) in PARAMETERS.items():
            self.declare_parameter(name, default, ParameterDescriptor(description=text))
        self.add_on_set_parameters_callback(self._on_set_parameters)

        self._lock = threading.Lock()
        self._wake = threading.Condition(self._lock)
        self._assembler: CycleAssembler[SliceFields] = CycleAssembler(
            sink=lambda _cycle_id, first: CyclePacker(first, self._ship_time_s))
        self._forecast = None
        self._cycle_id = ""
        self._ship: ShipState | None = None
        self._plan: RoutePlan | None = None
        self._plan_wall = 0.0
        self._last_replan_ship_s = -math.inf
        self._pending: str | None = None
        self._cancel = threading.Event()
        self._planning = False
        self._last_error = ""
        self._progress: dict[str, float] = {}
        self._plans_made = 0
        self._done_event = threading.Condition(threading.Lock())
        self._stop = False
        self._cycle_timing: dict[str, list[float]] = {}  # first slice arrival, packing [s]
        self._trim_memory = False

        io_group = ReentrantCallbackGroup()
        # the forecast arrives on a node of its own, spun by a single-threaded executor (see
        # `main`): packed in arrival order as they come, and ~2x faster per slice than through the
        # multi-threaded executor's thread pool (0.20 vs 0.27-0.59 s for a 129-slice cycle)
        self.intake = rclpy.create_node(
            f"{self.get_name()}_forecast_intake", namespace=self.get_namespace(),
            context=self.context, use_global_arguments=False)  # not renamed like this node
        self.intake.create_subscription(
            ForecastCycle, self.resolve_topic_name("/shiproute/forecast/cycle"), self._on_cycle,
            LATCHED)
        self.intake.create_subscription(ForecastSlice, self.resolve_topic_name(SLICES_TOPIC),
                                        self._on_slice, SLICES)
        self.create_subscription(ShipState, "/shiproute/ship_state", self._on_ship_state, STATE,
                                 callback_group=io_group)
        self._pub_path = self.create_publisher(PathMsg, "/shiproute/plan/path", LATCHED)
        self._pub_rpm = self.create_publisher(RpmProfile, "/shiproute/plan/rpm_profile", LATCHED)
        self._pub_plan = self.create_publisher(RoutePlanMsg, "/shiproute/plan/route", LATCHED)
        self._pub_diag = self.create_publisher(DiagnosticArray, "/diagnostics", 10)
        self.create_service(SetVoyage, "/shiproute/planner/set_voyage", self._on_set_voyage,
                            callback_group=io_group)
        self._action = ActionServer(
            self, PlanRoute, "/shiproute/planner/plan", self._execute_goal,
            goal_callback=lambda _g: GoalResponse.ACCEPT,
            cancel_callback=lambda _g: CancelResponse.ACCEPT,
            callback_group=ReentrantCallbackGroup(),
        )
        self.create_timer(1.0, self._tick, callback_group=MutuallyExclusiveCallbackGroup())
        self._worker = threading.Thread(target=self._work, name="planner", daemon=True)
        self._worker.start()
        self._log_seed_pool()
        self.get_logger().info("planner ready; waiting for a complete forecast cycle")

    def _log_seed_pool(self) -> None:
        """Say what the persisted seed pool holds, so a restart visibly continues from it."""
        directory = str(self._p("seed_pool_dir"))
        if not directory:
            return
        from .ga.pool import POOL_FILE, SeedPool

        try:
            n = len(SeedPool(directory))
        except Exception as err:  # a damaged pool is reported; planning goes on without it
            self.get_logger().error(f"seed pool in {directory} unreadable: {err}")
            return
        self.get_logger().info(f"seed pool: {n} seed(s) in {Path(directory) / POOL_FILE}")

    # ----------------------------------------------------------------- parameters
    def _p(self, name: str):
        return self.get_parameter(name).value

    def _on_set_parameters(self, params) -> SetParametersResult:
        for p in params:
            reason = check_parameter(p.name, p.value)
            if reason is not None:
                self.get_logger().warning(f"rejected parameter: {reason}")
                return SetParametersResult(successful=False, reason=reason)
        return SetParametersResult(successful=True)

    def _on_set_voyage(self, req: SetVoyage.Request, res: SetVoyage.Response):
        dest = req.destination.strip() or f"{req.destination_lat_deg},{req.destination_lon_deg}"
        rta_s = posix_s(req.rta)
        from datetime import UTC, datetime

        updates = [rclpy.parameter.Parameter("destination", value=dest)]
        if rta_s > 0:
            rta_iso = datetime.fromtimestamp(rta_s, UTC).isoformat().replace("+00:00", "Z")
            updates.append(rclpy.parameter.Parameter("rta", value=rta_iso))
        if req.ship:
            updates.append(rclpy.parameter.Parameter("ship", value=req.ship))
        if req.objective:
            updates.append(rclpy.parameter.Parameter("objective", value=req.objective))
        result = self.set_parameters_atomically(updates)
        res.accepted = bool(result.successful)
        res.message = result.reason if not result.successful else f"voyage to {dest} set"
        if res.accepted:
            self._request("voyage set")
        return res

    # ----------------------------------------------------------------- inputs
    def _on_cycle(self, msg: ForecastCycle) -> None:
        # what the cycle holds and where from: stated by every plan made on it
        self._cycle_records = {msg.cycle_id: cycle_record(msg)}
        self._feed(msg.cycle_id, _ANNOUNCEMENT, int(msg.slice_count), None)

    def _on_slice(self, msg: ForecastSlice) -> None:
        # a zero-copy view: packed straight from the message's buffers
        self._cycle_timing.setdefault(msg.cycle_id, [time.monotonic(), 0.0])
        self._feed(msg.cycle_id, int(msg.slice_index), int(msg.slice_count), slice_fields(msg))

    def _feed(self, cycle_id: str, index: int, count: int, item: SliceFields | None) -> None:
        """An announcement or a slice into the assembler, on the forecast intake's one thread
        (the only one that touches it; the packing kernel runs without the GIL), and the
        cycle it completes, if any, into planning. Packing here, not on a thread of its own,
        spares a GIL hand-over per slice (a packer thread took 2.5-3.6 ms per slice against
        0.9 ms of work)."""
        t0 = time.monotonic()
        try:
            if index == _ANNOUNCEMENT:
                sampler = self._assembler.announce(cycle_id, count)
            else:
                sampler = self._assembler.add_slice(cycle_id, index, count, item)
        except Exception as err:  # a bad slice or cycle must not stop the intake
            self._reject_cycle(cycle_id, err)
            return
        finally:
            timing = self._cycle_timing.get(cycle_id)
            if timing is not None:
                timing[1] += time.monotonic() - t0
        self._take(sampler, cycle_id)

    def _ship_time_s(self) -> float:
        """Time of the last ship state (-inf before the first): older slices are not kept."""
        pos = ship_position(self._ship) if self._ship is not None else None
        return pos[2] if pos is not None else -math.inf

    def _reject_cycle(self, cycle_id: str, err: Exception) -> None:
        """A bad slice or cycle is reported; planning goes on with the last good cycle."""
        self._cycle_timing.pop(cycle_id, None)
        self._last_error = f"forecast cycle {cycle_id!r} unusable: {err}"
        self.get_logger().error(self._last_error)

    def _take(self, sampler, cycle_id: str) -> None:
        """A complete cycle's sampler replaces the current one and triggers a re-plan."""
        if sampler is None:
            return
        sampler.record = getattr(self, "_cycle_records", {}).get(cycle_id)
        with self._lock:
            self._forecast, self._cycle_id = sampler, cycle_id
            if self._planning:
                self._cancel.set()  # supersede the running plan
        self._request(f"new forecast cycle {cycle_id}")
        first_s, pack_s = self._cycle_timing.pop(cycle_id, (time.monotonic(), 0.0))
        self.get_logger().info(
            f"forecast cycle {cycle_id} complete: {sampler.times_s.size} slices kept "
            f"({sampler.nbytes / 2**20:.0f} MiB), received over {time.monotonic() - first_s:.2f} s"
            f" ({pack_s:.2f} s unpacking)")
        _return_freed_memory(collect=False)  # the slice buffers: freed, not yet returned
        self._trim_memory = True

    def _on_ship_state(self, msg: ShipState) -> None:
        if ship_position(msg) is None:
            return
        first = self._ship is None
        self._ship = msg
        if first:
            self._request("first ship state")

    # ----------------------------------------------------------------- triggers
    def _request(self, reason: str) -> None:
        with self._wake:
            self._pending = reason
            self._wake.notify()

    def _tick(self) -> None:
        self._check_off_plan()
        self._publish_diagnostics()

    def _check_off_plan(self) -> None:
        plan, ship = self._plan, self._ship
        if plan is None or ship is None or self._planning or self._pending:
            return
        pos = ship_position(ship)
        if pos is None or pos[2] >= plan.eta_s:
            return
        if pos[2] - self._last_replan_ship_s < float(self._p("min_replan_interval_s")):
            return
        lon, lat, t = plan.track()
        dev = track_deviation(lat, lon, t, pos[0], pos[1], pos[2])
        thresholds = ReplanThresholds(
            float(self._p("replan_cross_track_nm")), float(self._p("replan_schedule_h")) * 3600
        )
        reasons = thresholds.exceeded(dev)
        if reasons:
            self._last_replan_ship_s = pos[2]
            self._request("off plan: " + "; ".join(reasons))

    # ----------------------------------------------------------------- planning
    def _snapshot(self, reason: str) -> _Inputs | None:
        if self._forecast is None:
            return None
        pos = ship_position(self._ship) if self._ship is not None else None
        if pos is None and not self._p("plan_without_ship_state"):
            return None
        return _Inputs(self._forecast, self._cycle_id, pos, self._plan, reason)

    def _work(self) -> None:
        while True:
            with self._wake:
                while self._pending is None and not self._stop:
                    self._wake.wait(0.5)
                if self._stop:
                    return
                reason, self._pending = self._pending, None
                inputs = self._snapshot(reason)
                if inputs is None:
                    continue
                self._planning = True
                self._cancel.clear()
            try:
                self._plan_once(inputs)
            except Exception as err:  # the node never dies on input
                self._last_error = f"planning failed ({inputs.reason}): {err}"
                self.get_logger().error(self._last_error)
            finally:
                with self._done_event:
                    self._planning = False
                    self._done_event.notify_all()

    def _plan_once(self, inputs: _Inputs) -> None:
        from .planning import plan_voyage

        origin = str(self._p("origin"))
        position = inputs.position
        depart: float
        if position is None:
            depart = parse_utc(str(self._p("departure_time")))
        else:
            depart = position[2]
            if inputs.previous is None and self._near_origin(origin, position):
                position = None  # at the departure port: plan from the port (pool key by ports)
        pool = str(self._p("seed_pool_dir")) or None
        self._progress = {}
        self.get_logger().info(f"planning ({inputs.reason}) on cycle {inputs.cycle_id}")
        plan = plan_voyage(
            origin, str(self._p("destination")), depart, parse_utc(str(self._p("rta"))),
            str(self._p("ship")), inputs.forecast, cycle_id=inputs.cycle_id,
            objective=str(self._p("objective")), method=str(self._p("method")),
            budget_s=float(self._p("budget_s")), seed=int(self._p("rng_seed")),
            stage_hours=float(self._p("stage_hours")), previous_plan=inputs.previous,
            position=position, seed_pool_dir=pool, progress=self._on_progress,
            cancel=self._cancel, ship_model=str(self._p("ship_model")),
            bathymetry=_paths(str(self._p("bathymetry_files"))),
            default_bathymetry=bool(self._p("default_bathymetry")),
            ukc_margin_m=float(self._p("ukc_margin_m")),
            zones=_paths(str(self._p("zones_files"))),
            clearance_nm=float(self._p("clearance_nm")),
            approaches_given=_paths(str(self._p("approach_files"))),
        )
        if self._cancel.is_set():
            self.get_logger().info(f"plan on {inputs.cycle_id} superseded by a newer cycle")
            return
        self._publish(plan, inputs)
        # after publishing: files, then the freed buffers of a new cycle back to the OS
        self._write_outputs(plan, inputs.forecast)
        if self._trim_memory:
            self._trim_memory = False
            _return_freed_memory()  # a full collection first
            _freeze_long_lived()  # after the first plan, which loaded all planning needs
            rss, peak = _memory_mb()
            self.get_logger().info(f"planner memory: {rss:.0f} MiB resident, peak {peak:.0f} MiB")

    def _near_origin(self, origin: str, pos: tuple[float, float, float]) -> bool:
        """Whether the ship is still at the departure port (within departure_radius_nm)."""
        from .geo.geodesy import inverse
        from .geo.landmask import default_land_mask
        from .geo.ports import resolve_port

        try:
            port = resolve_port(origin, default_land_mask())
        except Exception:  # an unknown origin just means "plan from the ship"
            return False
        _, dist_m = inverse(port.lon_deg, port.lat_deg, pos[1], pos[0])
        return float(dist_m) / 1852.0 <= float(self._p("departure_radius_nm"))

    def _on_progress(self, progress) -> None:
        self._progress = {
            "generation": float(getattr(progress, "generation", 0)),
            "evaluations": float(getattr(progress, "evaluations", 0)),
            "best_objective": float(getattr(progress, "best_objective", math.nan)),
        }

    def _publish(self, plan: RoutePlan, inputs: _Inputs) -> None:
        stamp = self.get_clock().now().to_msg()
        self._pub_path.publish(plan_to_path(plan, stamp))
        self._pub_rpm.publish(plan_to_rpm_profile(plan, stamp))
        plan_msg = plan_to_msg(plan, stamp)
        plan_msg.trigger = inputs.reason  # shown in the bridge display's re-plan history
        self._pub_plan.publish(plan_msg)
        self._plan, self._plan_wall = plan, time.monotonic()
        self._plans_made += 1
        saved = plan.fuel_saving_t
        self.get_logger().info(
            f"plan {plan.plan_id} cycle {plan.cycle_id}: fuel {plan.total_fuel_t:.1f} t, "
            f"ETA-RTA {(plan.eta_s - plan.rta_s) / 3600:+.1f} h, saved {saved:.1f} t vs "
            f"constant RPM, {plan.compute_time_s:.2f} s, feasible={plan.feasible} "
            f"({inputs.reason})"
        )

    def _write_outputs(self, plan: RoutePlan, sampler) -> None:
        out = str(self._p("output_dir"))
        if not out:
            return
        try:
            from .io.files import write_plan_files

            png = bool(self._p("write_png"))
            hs = hs_field_at(sampler, plan.departure_s) if png else None
            write_plan_files(plan, Path(out), forecast=hs, png=png)
        except Exception as err:  # file output must not stop planning
            self._last_error = f"writing plan files to {out} failed: {err}"
            self.get_logger().error(self._last_error)

    # ----------------------------------------------------------------- action
    def _execute_goal(self, goal_handle):
        before = self._plans_made
        if goal_handle.request.budget_s > 0:
            self.set_parameters([rclpy.parameter.Parameter(
                "budget_s", value=float(goal_handle.request.budget_s))])
        self._request(goal_handle.request.reason or "plan requested")
        result = PlanRoute.Result()
        start = time.monotonic()
        deadline = start + 10.0 * float(self._p("budget_s")) + 30.0
        while time.monotonic() < deadline:
            if goal_handle.is_cancel_requested:
                self._cancel.set()
                goal_handle.canceled()
                result.message = "cancelled"
                return result
            if self._plans_made > before and not self._planning:
                goal_handle.succeed()
                result.success = True
                result.plan_id = self._plan.plan_id if self._plan else ""
                result.message = "planned"
                return result
            fb = PlanRoute.Feedback()
            fb.generation = int(self._progress.get("generation", 0))
            fb.evaluations = int(self._progress.get("evaluations", 0))
            fb.best_fuel_t = float(self._progress.get("best_objective", math.nan))
            fb.elapsed_s = time.monotonic() - start
            goal_handle.publish_feedback(fb)
            with self._done_event:
                self._done_event.wait(0.2)
        goal_handle.abort()
        result.message = self._last_error or "no plan: waiting for a forecast cycle or ship state"
        return result

    # ----------------------------------------------------------------- diagnostics
    def _publish_diagnostics(self) -> None:
        plan = self._plan
        status = DiagnosticStatus(name="shiproute_planner", hardware_id="shiproute")
        values = {
            "forecast_cycle": self._cycle_id or "none",
            "planning": str(self._planning),
            "plans_made": str(self._plans_made),
            "last_error": self._last_error,
        }
        if plan is None:
            status.level = DiagnosticStatus.WARN
            status.message = "no plan yet"
        else:
            status.level = DiagnosticStatus.OK if plan.feasible else DiagnosticStatus.WARN
            status.message = "plan feasible" if plan.feasible else "; ".join(
                plan.infeasible_reasons)
            values.update({
                "plan_id": plan.plan_id,
                "plan_cycle": plan.cycle_id,
                "plan_age_s": f"{time.monotonic() - self._plan_wall:.1f}",
                "compute_time_s": f"{plan.compute_time_s:.3f}",
                "feasible": str(plan.feasible),
                "constraints": ", ".join(plan.infeasible_reasons) or "all met",
                "warnings": "; ".join(plan.warnings) or "none",
                "fuel_t": f"{plan.total_fuel_t:.2f}",
                "eta_minus_rta_h": f"{(plan.eta_s - plan.rta_s) / 3600:.2f}",
            })
        status.values = [KeyValue(key=k, value=v) for k, v in values.items()]
        msg = DiagnosticArray(status=[status])
        msg.header.stamp = self.get_clock().now().to_msg()
        self._pub_diag.publish(msg)

    def shutdown(self) -> None:
        with self._wake:
            self._stop = True
            self._cancel.set()
            self._wake.notify()
        self._worker.join(timeout=5.0)


def _spin_quietly(executor: SingleThreadedExecutor) -> None:
    """Spin until the context shuts down (Ctrl-C and SIGTERM end the main executor)."""
    with contextlib.suppress(KeyboardInterrupt, ExternalShutdownException):
        executor.spin()


def main(args: list[str] | None = None) -> int:
    """Console entry point `shiproute_planner_node [--ros-args ...]`."""
    _return_large_blocks_at_once()
    # hand the GIL over every 1 ms instead of 5: the forecast intake thread otherwise waits
    # up to 5 ms per slice behind the executor threads; the planner's other threads spend
    # their time in compiled code without the GIL
    sys.setswitchinterval(0.001)
    profile = use_dynamic_slice_buffers(SLICES_TOPIC)
    rclpy.init(args=sys.argv if args is None else args)
    node = PlannerNode()
    forget_profile(profile)
    executor = MultiThreadedExecutor(num_threads=4)
    executor.add_node(node)
    intake = SingleThreadedExecutor()
    intake.add_node(node.intake)
    threading.Thread(target=_spin_quietly, args=(intake,), name="forecast intake",
                     daemon=True).start()
    try:
        executor.spin()
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        node.shutdown()
        intake.shutdown()
        executor.shutdown()
        node.intake.destroy_node()
        node.destroy_node()
        if rclpy.ok():
            rclpy.try_shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
