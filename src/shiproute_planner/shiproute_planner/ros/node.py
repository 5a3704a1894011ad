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

from ..checks.forecast_wire import check_not_older, check_slice_count, check_slice_fields
from ..checks.parameters import check_number
from ..checks.ship_state import check_ship_state
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
from .drop_log import DropLog
from ..errors import PlannerError
from .intake_keys import RejectedKeys, assembly_key
from ..plan_types import RoutePlan
from .replan_policy import ReplanThresholds, track_deviation
from ..voyage_params import check_parameter, parse_utc
from ..voyage_request import VoyageRequest, check_voyage_request

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
# the reader keeps several announcements: with depth 1 one that arrives while the intake is
# busy packing the previous cycle's slices is overwritten, and its cycle never completes
ANNOUNCEMENTS = QoSProfile(
    depth=8,
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
    "accept_older_forecasts": (False, "let a cycle of an older model run replace the one in "
                               "force (e.g. to go back after a bad run)"),
    "ship_state_max_age_h": (366 * 24.0, "drop ship states older than this behind the clock [h]"),
    "ship_state_max_lead_h": (1.0, "drop ship states further ahead of the clock than this [h]"),
}
DROP_KINDS = ("ship_states", "forecast_slices", "forecast_cycles", "voyage_requests",
              "plan_requests")


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
    budget_s: float | None = None  # a PlanRoute goal's own budget (None: the parameter)
    request_seq: int = 0  # the latest request this run answers


class PlannerNode(Node):
    """Thin ROS shell around `shiproute_planner.planning.plan_voyage`."""

    def __init__(self) -> None:
        super().__init__("shiproute_planner")
        for name, (default, text) in PARAMETERS.items():
            self.declare_parameter(name, default, ParameterDescriptor(description=text))
        self.add_on_set_parameters_callback(self._on_set_parameters)

        self._lock = threading.Lock()
        self._wake = threading.Condition(self._lock)
        self._drops = DropLog(DROP_KINDS)
        # at most two cycles in flight (a superseded one's tail and its successor): each holds
        # a sampler array being filled beside the one in force
        self._assembler: CycleAssembler[SliceFields] = CycleAssembler(
            max_pending_cycles=2, sink=self._new_packer, on_evict=self._on_evict)
        self._rejected = RejectedKeys()
        self._forecast = None
        self._cycle_id = ""
        self._cycle_reference_s = 0.0  # reference time of the cycle in force (0: unknown)
        self._cycles_accepted = 0
        self._last_cycle_refusal = ""
        # requests and their outcomes, so a PlanRoute goal waits for the run that answers it
        self._request_seq = 0
        self._pending_budget_s: float | None = None
        self._answered_seq = 0
        self._answer_ok = False
        self._answer_text = ""
        self._plans_failed = 0
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
            ANNOUNCEMENTS)
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
        self._load_bathymetry()
        self.get_logger().info("planner ready; waiting for a complete forecast cycle")

    def _load_bathymetry(self) -> None:
        """Read the depth grids now (they are cached per process), so the first plan's budget
        is spent planning; a bad grid is reported here and again by the plan that meets it."""
        from ..geo.depth import load_bathymetry

        try:
            bathy = load_bathymetry(_paths(str(self._p("bathymetry_files"))),
                                    with_default=bool(self._p("default_bathymetry")))
        except PlannerError as err:
            self._last_error = f"bathymetry: {err}"
            self.get_logger().error(self._last_error)
            return
        self.get_logger().info("depth: " + ("no bathymetry grid (depth not checked)"
                                            if bathy is None else "bathymetry grids loaded"))

    def _log_seed_pool(self) -> None:
        """Say what the persisted seed pool holds, so a restart visibly continues from it."""
        directory = str(self._p("seed_pool_dir"))
        if not directory:
            return
        from ..ga.pool import POOL_FILE, SeedPool

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
            if reason is None and p.name == "method":
                reason = _method_reason(str(p.value))
            if reason is not None:
                self.get_logger().warning(f"rejected parameter: {reason}")
                return SetParametersResult(successful=False, reason=reason)
        return SetParametersResult(successful=True)

    def _on_set_voyage(self, req: SetVoyage.Request, res: SetVoyage.Response):
        """Check the whole voyage first; answer accepted=false with the reason when it is
        invalid, accepted=true (with the RTA warning when it cannot be met) otherwise."""
        request = VoyageRequest(
            destination=req.destination, destination_lat_deg=float(req.destination_lat_deg),
            destination_lon_deg=float(req.destination_lon_deg), rta_s=posix_s(req.rta),
            ship=req.ship, objective=req.objective)
        try:
            checked = check_voyage_request(
                request, origin=str(self._p("origin")), ship=str(self._p("ship")),
                objective=str(self._p("objective")), method=str(self._p("method")),
                rta=str(self._p("rta")), position=self._fix(),
                departure_time=str(self._p("departure_time")), clock_s=self._clock_s())
        except Exception as err:  # every refusal is an answer, never an exception
            reason = str(err) if isinstance(err, PlannerError | ValueError) else repr(err)
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
    def _on_cycle(self, msg: ForecastCycle) -> None:
        key = assembly_key(msg.cycle_id, msg.publication_id)
        try:
            check_slice_count(msg.cycle_id, int(msg.slice_count))
        except PlannerError as err:
            self._reject_cycle(key, msg.cycle_id, err)
            return
        # what the cycle holds and where from: stated by every plan made on it
        records = getattr(self, "_cycle_records", {})
        records[msg.cycle_id] = cycle_record(msg)
        self._cycle_records = dict(list(records.items())[-8:])
        self._feed(key, msg.cycle_id, _ANNOUNCEMENT, int(msg.slice_count), None)

    def _on_slice(self, msg: ForecastSlice) -> None:
        # a zero-copy view: packed straight from the message's buffers
        key = assembly_key(msg.cycle_id, msg.publication_id)
        self._cycle_timing.setdefault(key, [time.monotonic(), 0.0])
        self._feed(key, msg.cycle_id, int(msg.slice_index), int(msg.slice_count),
                   slice_fields(msg))

    def _feed(self, key: str, cycle_id: str, index: int, count: int,
              item: SliceFields | None) -> None:
        """An announcement or a slice into the assembler, on the forecast intake's one thread
        (the only one that touches it; the packing kernel runs without the GIL), and the
        cycle it completes, if any, into planning. Every slice is checked before anything is
        allocated for it; the slices of a refused cycle are counted and dropped. Packing here,
        not on a thread of its own, spares a GIL hand-over per slice (a packer thread took
        2.5-3.6 ms per slice against 0.9 ms of work)."""
        if key in self._rejected:
            if item is not None:
                self._drops.drop("forecast_slices", f"cycle {cycle_id!r} was refused: "
                                 f"{self._rejected.reason(key)}")
            return
        t0 = time.monotonic()
        try:
            if index == _ANNOUNCEMENT:
                sampler = self._assembler.announce(key, count)
            else:
                assert item is not None
                check_slice_fields(item)
                sampler = self._assembler.add_slice(key, index, count, item)
        except Exception as err:  # a bad slice or cycle must not stop the intake
            self._reject_cycle(key, cycle_id, err, slices=0 if item is None else 1)
            return
        finally:
            timing = self._cycle_timing.get(key)
            if timing is not None:
                timing[1] += time.monotonic() - t0
        self._take(sampler, key, cycle_id)

    def _new_packer(self, _key: str, first: SliceFields) -> CyclePacker:
        """The sampler array of a new cycle, made from its first (checked) slice once it is
        known not to be older than the cycle in force."""
        self._check_fresh(first.cycle_id, first.reference_time_s)
        return CyclePacker(first, self._ship_time_s)

    def _check_fresh(self, cycle_id: str, reference_s: float) -> None:
        if not self._p("accept_older_forecasts"):
            check_not_older(cycle_id, reference_s, self._cycle_id, self._cycle_reference_s)

    def _on_evict(self, key: str, received: int) -> None:
        """An incomplete cycle pushed out by newer ones: its slices are dropped, counted."""
        self._cycle_timing.pop(key, None)
        reason = f"cycle {key!r} incomplete ({received} slice(s)) when newer cycles arrived"
        self._drops.drop("forecast_cycles", reason)
        if received:
            self._drops.drop("forecast_slices", reason, received)
        self._last_cycle_refusal = reason

    def _ship_time_s(self) -> float:
        """Time of the last ship state (-inf before the first): older slices are not kept."""
        pos = ship_position(self._ship) if self._ship is not None else None
        return pos[2] if pos is not None else -math.inf

    def _reject_cycle(self, key: str, cycle_id: str, err: Exception, slices: int = 0) -> None:
        """A bad slice or cycle is reported and counted; the cycle in force stays."""
        self._cycle_timing.pop(key, None)
        self._rejected.add(key, str(err))
        self._assembler.discard(key)  # not also counted as incomplete later
        kept = self._cycle_id or "none"
        self._last_error = f"forecast cycle {cycle_id!r} refused ({kept} stays in force): {err}"
        self._last_cycle_refusal = self._last_error
        self._drops.drop("forecast_cycles", str(err))
        if slices:
            self._drops.drop("forecast_slices", str(err), slices)
        self.get_logger().error(self._last_error)

    def _take(self, sampler, key: str, cycle_id: str) -> None:
        """A complete cycle's sampler replaces the current one and triggers a re-plan (unless
        a newer model run came into force while it streamed in)."""
        if sampler is None:
            return
        sampler.record = getattr(self, "_cycle_records", {}).get(cycle_id)
        reference_s = float(getattr(sampler, "reference_time_s", 0.0))
        try:
            self._check_fresh(cycle_id, reference_s)
        except PlannerError as err:
            self._reject_cycle(key, cycle_id, err)
            return
        with self._lock:
            self._forecast, self._cycle_id = sampler, cycle_id
            self._cycle_reference_s = reference_s
            self._cycles_accepted += 1
            if self._planning:
                self._cancel.set()  # supersede the running plan
        self._request(f"new forecast cycle {cycle_id}")
        first_s, pack_s = self._cycle_timing.pop(key, (time.monotonic(), 0.0))
        self.get_logger().info(
            f"forecast cycle {cycle_id} complete: {sampler.times_s.size} slices kept "
            f"({sampler.nbytes / 2**20:.0f} MiB), received over {time.monotonic() - first_s:.2f} s"
            f" ({pack_s:.2f} s unpacking)")
        _return_freed_memory(collect=False)  # the slice buffers: freed, not yet returned
        self._trim_memory = True

    def _clock_s(self) -> float:
        """The node's clock [POSIX s] (0 with simulated time before the first /clock)."""
        return self.get_clock().now().nanoseconds * 1e-9

    def _fix(self) -> tuple[float, float, float] | None:
        """(lat, lon, time) of the last accepted ship state, None before one."""
        return ship_position(self._ship) if self._ship is not None else None

    def _on_ship_state(self, msg: ShipState) -> None:
        """Checked before it is taken: a refused fix is counted with its reason and logged
        (throttled); the last good one stays."""
        optional = {name: float(getattr(msg, name)) for name in (
            "sog_kn", "cog_deg", "heading_deg", "stw_kn", "shaft_rpm", "draft_fore_m",
            "draft_aft_m", "fuel_rate_t_per_h")}
        try:
            check_ship_state(
                float(msg.latitude_deg), float(msg.longitude_deg), posix_s(msg.header.stamp),
                optional, clock_s=self._clock_s(),
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
    def _request(self, reason: str, budget_s: float | None = None) -> int:
        """Ask the worker for a plan; returns the request's number (a goal waits for it)."""
        with self._wake:
            self._pending = reason
            self._request_seq += 1
            if budget_s is not None:
                self._pending_budget_s = budget_s  # kept until a run takes it
            self._wake.notify()
            return self._request_seq

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
    def _snapshot(self, reason: str) -> _Inputs | str:
        """What to plan on, or why nothing can be planned yet."""
        if self._forecast is None:
            return "no plan: no complete forecast cycle received yet"
        pos = self._fix()
        if pos is None and not self._p("plan_without_ship_state"):
            return "no plan: no valid ship state received yet"
        budget, self._pending_budget_s = self._pending_budget_s, None
        return _Inputs(self._forecast, self._cycle_id, pos, self._plan, reason, budget,
                       self._request_seq)

    def _answer(self, seq: int, ok: bool, text: str) -> None:
        """Record the outcome of the run that served requests up to `seq`."""
        with self._done_event:
            self._answered_seq, self._answer_ok, self._answer_text = seq, ok, text
            self._done_event.notify_all()

    def _work(self) -> None:
        while True:
            with self._wake:
                while self._pending is None and not self._stop:
                    self._wake.wait(0.5)
                if self._stop:
                    return
                reason, self._pending = self._pending, None
                inputs = self._snapshot(reason)
                if isinstance(inputs, str):
                    self._answer(self._request_seq, False, inputs)
                    continue
                self._planning = True
                self._cancel.clear()
            try:
                if self._plan_once(inputs):
                    self._answer(inputs.request_seq, True, self._plan.plan_id if self._plan
                                 else "")
            except Exception as err:  # the node never dies on input
                self._last_error = f"planning failed ({inputs.reason}): {err}"
                self._plans_failed += 1
                self.get_logger().error(self._last_error)
                self._answer(inputs.request_seq, False, self._last_error)
            finally:
                with self._done_event:
                    self._planning = False
                    self._done_event.notify_all()

    def _plan_once(self, inputs: _Inputs) -> bool:
        """Plan and publish; False when the run was superseded by a newer cycle."""
        from ..planning import plan_voyage

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
            budget_s=inputs.budget_s if inputs.budget_s is not None
            else float(self._p("budget_s")), seed=int(self._p("rng_seed")),
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
            return False
        self._publish(plan, inputs)
        # after publishing: files, then the freed buffers of a new cycle back to the OS
        self._write_outputs(plan, inputs.forecast)
        if self._trim_memory:
            self._trim_memory = False
            _return_freed_memory()  # a full collection first
            _freeze_long_lived()  # after the first plan, which loaded all planning needs
            rss, peak = _memory_mb()
            self.get_logger().info(f"planner memory: {rss:.0f} MiB resident, peak {peak:.0f} MiB")
        return True

    def _near_origin(self, origin: str, pos: tuple[float, float, float]) -> bool:
        """Whether the ship is still at the departure port (within departure_radius_nm)."""
        from shiproute_core.geodesy import inverse

        from ..geo.landmask import default_land_mask
        from ..geo.ports import resolve_port

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
            from ..io.files import write_plan_files

            png = bool(self._p("write_png"))
            hs = hs_field_at(sampler, plan.departure_s) if png else None
            write_plan_files(plan, Path(out), forecast=hs, png=png)
        except Exception as err:  # file output must not stop planning
            self._last_error = f"writing plan files to {out} failed: {err}"
            self.get_logger().error(self._last_error)

    # ----------------------------------------------------------------- action
    def _execute_goal(self, goal_handle):
        """Plan for this goal (with its own budget, the parameter untouched) and end as soon
        as the run that answers it ends: succeeded with the plan, or aborted with the reason."""
        result = PlanRoute.Result()
        budget = float(goal_handle.request.budget_s)
        reason = check_number("budget_s", budget) if budget != 0.0 else None
        if reason is not None:
            self._drops.drop("plan_requests", reason)
            goal_handle.abort()
            result.message = f"goal refused: {reason}"
            return result
        goal_budget = budget if budget > 0 else float(self._p("budget_s"))
        seq = self._request(goal_handle.request.reason or "plan requested",
                            budget if budget > 0 else None)
        start = time.monotonic()
        deadline = start + 10.0 * goal_budget + 60.0  # a stuck run (never seen) still ends
        while time.monotonic() < deadline:
            if goal_handle.is_cancel_requested:
                self._cancel.set()
                goal_handle.canceled()
                result.message = "cancelled"
                return result
            with self._done_event:
                answered, ok, text = self._answered_seq, self._answer_ok, self._answer_text
            if answered >= seq:
                result.success, result.message = ok, "planned" if ok else text
                result.plan_id = text if ok else ""
                if ok:
                    goal_handle.succeed()
                else:
                    self._drops.drop("plan_requests", text)
                    goal_handle.abort()
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
        result.message = f"no answer within {deadline - start:.0f} s: {self._last_error}"
        return result

    # ----------------------------------------------------------------- diagnostics
    def _publish_diagnostics(self) -> None:
        plan = self._plan
        status = DiagnosticStatus(name="shiproute_planner", hardware_id="shiproute")
        values = {
            "forecast_cycle": self._cycle_id or "none",
            "forecast_cycle_in_force": self._cycle_id or "none",
            "forecast_reference_time_s": f"{self._cycle_reference_s:.0f}",
            "forecast_cycles_accepted": str(self._cycles_accepted),
            "forecast_last_refusal": self._last_cycle_refusal or "none",
            "planning": str(self._planning),
            "plans_made": str(self._plans_made),
            "plans_failed": str(self._plans_failed),
            "last_error": self._last_error,
            **self._drops.values(),
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


def _method_reason(name: str) -> str | None:
    """Why `name` is not a route-finding method (None when it is)."""
    from ..errors import UnknownMethodError
    from ..methods import get_method

    try:
        get_method(name)
    except UnknownMethodError as err:
        return str(err)
    return None


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
