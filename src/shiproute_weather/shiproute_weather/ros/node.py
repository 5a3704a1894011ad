"""Weather node: loads forecast cycles (files, watched directory, service) and serves them.

Topics (names in `shiproute_core.topics`, see README.md): FORECAST_CYCLE (ForecastCycle,
reliable, transient-local, depth 1), FORECAST_SLICES (ForecastSlice, reliable,
transient-local, depth = max_slices), DIAGNOSTICS (DiagnosticArray). Service: FORECAST_LOAD
(LoadForecast).
"""

from __future__ import annotations

import queue
import sys
import threading
import time
import uuid
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import rclpy
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue
from rcl_interfaces.msg import ParameterDescriptor, SetParametersResult
from rclpy.callback_groups import MutuallyExclusiveCallbackGroup, ReentrantCallbackGroup
from rclpy.executors import MultiThreadedExecutor
from rclpy.node import Node
from rclpy.parameter import Parameter
from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy
from shiproute_core.spin import spin_until_shutdown
from shiproute_core.topics import DIAGNOSTICS, FORECAST_CYCLE, FORECAST_LOAD, FORECAST_SLICES

from shiproute_msgs.msg import ForecastCycle, ForecastSlice
from shiproute_msgs.srv import LoadForecast

from ..errors import WeatherError
from ..ingest.combine import Box
from ..ingest.cycle_builder import MAX_SLICE_BYTES, MAX_SLICES, CycleConfig, corridor_box
from ..ingest.cycle_load import load_cycle
from ..ingest.members import member_file_groups
from ..ingest.stream import warm_array_backends
from ..ingest.watch import DirectoryWatcher
from ..ingest.wire_budget import wire_summary
from ..scenarios.catalogue import scenario_path
from .convert import (
    DEFAULT_SLICE_ENCODING,
    SLICE_ENCODINGS,
    check_encoding,
    cycle_to_msg,
    slice_to_msg,
)
from .heap import resident_memory_mb, return_freed_memory, return_large_blocks_at_once
from .spool import SliceSpool, publish_spooled, spool_slice

DIAG_NAME = "shiproute_weather: forecast"


def latched(depth: int) -> QoSProfile:
    """Reliable + transient-local so late joiners receive the last `depth` messages."""
    return QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=depth,
                      reliability=ReliabilityPolicy.RELIABLE,
                      durability=DurabilityPolicy.TRANSIENT_LOCAL)


@dataclass
class LoadRequest:
    """Files forming one cycle, and where the request came from."""

    paths: list[str]
    origin: str
    done: threading.Event | None = None
    members: list[list[str]] | None = None  # files of each member of a multi-model cycle
    labels: tuple[str, ...] | None = None  # their labels (None: the start-up parameter's)
    result: tuple[bool, str, str] = (False, "", "")



def service_request_error(request: LoadForecast.Request) -> str | None:
    """Why a LoadForecast request cannot be a cycle (None when it can): files or members,
    not both; labels only with members."""
    if request.paths and request.member_files:
        return "give either paths (one cycle) or member_files (a multi-model cycle), not both"
    if request.member_labels and not request.member_files:
        return "member_labels given without member_files"
    if not request.paths and not any(str(e).strip() for e in request.member_files):
        return "no paths given"
    return None


def _list_value(param: Parameter) -> list[Any]:
    """A list parameter's values ([] when unset)."""
    values: list[Any] = list(param.value or [])
    return values

class WeatherNode(Node):
    """Thin ROS shell round `cycle_builder.build_cycle`; loading runs in a worker thread."""

    def __init__(self) -> None:
        super().__init__("shiproute_weather")
        p = self.declare_parameter
        files = _list_value(p("forecast_files", [""]))
        scenario = str(p("scenario", "").value)
        watch_dir = str(p("watch_dir", "").value)
        self.settle_s = float(p("settle_s", 1.0).value)
        watch_period_s = float(p("watch_period_s", 0.5).value)
        region = [float(x) for x in _list_value(p("region", [0.0]))]
        corridor = [float(x) for x in _list_value(p("corridor_lat_lon_deg", [0.0]))]
        margin = float(p("corridor_margin_deg", 5.0).value)
        self.max_slices = int(p("max_slices", MAX_SLICES).value)
        required = [str(x) for x in _list_value(p("required_fields", [""])) if x]
        members = member_file_groups(_list_value(p("member_files", [""], ParameterDescriptor(
            description="a multi-model cycle: one entry per member, its files joined by '+' "
                        "(e.g. gfs.grib2, ecmwf_wind.grib2+ecmwf_waves.grib2)"))))
        self.cfg_base = CycleConfig(
            box=self._box(region, corridor, margin),
            slice_interval_s=float(p("slice_interval_s", 0.0).value),
            grid_stride=int(p("grid_stride", 1).value), max_slices=self.max_slices,
            max_slice_bytes=int(p("max_slice_bytes", MAX_SLICE_BYTES).value),
            required=tuple(required), cycle_id=str(p("cycle_id", "").value),
            waves_from_wind=bool(p("estimate_waves_from_wind", True).value),
            max_members=int(p("max_members", 0, ParameterDescriptor(
                description="most members of an ensemble published (0: all); the first "
                            "ones are kept and the drop is stated")).value),
            member_labels=tuple(str(x) for x in _list_value(p("member_labels", [""])) if x))
        diag_period_s = float(p("diagnostics_period_s", 1.0).value)
        encoding = str(p("slice_encoding", DEFAULT_SLICE_ENCODING, ParameterDescriptor(
            description="field encoding of published slices: " + ", ".join(SLICE_ENCODINGS)
            + " (16-bit simple packing, half the bytes; or exact float32)")).value)
        reason = check_encoding(encoding)
        if reason is not None:  # a bad launch value: say so, serve with the default
            self.get_logger().error(f"rejected parameter: {reason}; using "
                                    f"{DEFAULT_SLICE_ENCODING}")
            self.set_parameters([Parameter("slice_encoding", value=DEFAULT_SLICE_ENCODING)])
        self.add_on_set_parameters_callback(self._on_set_parameters)
        self.publish_period_s = float(p("publish_period_s", 0.0).value)
        self.spool_dir = str(p("spool_dir", "", ParameterDescriptor(
            description="directory of the unlinked file holding a cycle's encoded slices "
                        "between load and publication (one cycle's wire bytes on disk; "
                        "'' = the system's temporary directory)")).value)

        self.cycle_pub = self.create_publisher(ForecastCycle, FORECAST_CYCLE, latched(1))
        self.slice_pub = self.create_publisher(ForecastSlice, FORECAST_SLICES,
                                               latched(self.max_slices))
        self.diag_pub = self.create_publisher(DiagnosticArray, DIAGNOSTICS, 10)
        self.srv_group = ReentrantCallbackGroup()
        self.create_service(LoadForecast, FORECAST_LOAD, self._on_load,
                            callback_group=self.srv_group)
        timers = MutuallyExclusiveCallbackGroup()
        self.create_timer(diag_period_s, self._publish_diagnostics, callback_group=timers)
        if self.publish_period_s > 0:
            self.create_timer(self.publish_period_s, self._republish, callback_group=timers)

        self.lock = threading.Lock()  # state, diagnostics and the cycle in force
        self.publish_lock = threading.Lock()  # one publication (or re-publication) at a time
        # each load is one publication: (this process's session, load number); subscribers
        # assemble slices per publication, so a reload is new and a restart never merges
        self.session = uuid.uuid4().hex[:12]
        self.loads = 0
        self.state: dict[str, str] = {"cycle_id": "", "slices": "0", "members": "0",
                                      "member_labels": "", "slice_encoding": "",
                                      "bytes_per_slice": "0", "cycle_wire_bytes": "0",
                                      "wire_budget": "", "load_path": "",
                                      "source_files": "", "load_s": "", "last_error": "",
                                      "notes": "", "cycles_published": "0",
                                      "publication_id": "", "loads_refused": "0",
                                      "loads_refused_last_reason": "none"}
        self.level = DiagnosticStatus.WARN
        self.message = "no forecast cycle loaded yet"
        # the cycle in force and its spooled slices, kept only to re-publish them
        self.current: tuple[ForecastCycle, SliceSpool] | None = None
        self.requests: queue.Queue[LoadRequest | None] = queue.Queue()
        self.worker = threading.Thread(target=self._work, name="forecast-loader", daemon=True)
        self.worker.start()

        self.watcher = DirectoryWatcher(Path(watch_dir), self.settle_s) if watch_dir else None
        initial = [f for f in files if f]
        if scenario:
            initial.append(str(scenario_path(scenario)))
        if self.watcher is not None:
            existing = self.watcher.mark_existing()
            if not initial and existing:
                initial = [str(x) for x in existing]
            self.create_timer(watch_period_s, self._poll_watch, callback_group=timers)
        if members:
            self.requests.put(LoadRequest([f for g in members for f in g], "member_files",
                                          members=members))
        elif initial:
            self.requests.put(LoadRequest(initial, "startup"))
        self.get_logger().info(f"ready: watching {watch_dir or '(nothing)'}, "
                               f"initial files {initial}")

    @staticmethod
    def _box(region: list[float], corridor: list[float], margin: float) -> Box | None:
        if len(region) == 4:
            return Box(*region)
        if len(corridor) >= 4 and len(corridor) % 2 == 0:
            return corridor_box(corridor[0::2], corridor[1::2], margin)
        return None

    def _on_set_parameters(self, params: list[Parameter]) -> SetParametersResult:
        """Reject a bad slice_encoding with the reason (the node keeps its current one)."""
        for prm in params:
            if prm.name == "slice_encoding":
                reason = check_encoding(str(prm.value))
                if reason is not None:
                    self.get_logger().warning(f"rejected parameter: {reason}")
                    return SetParametersResult(successful=False, reason=reason)
        return SetParametersResult(successful=True)

    def _poll_watch(self) -> None:
        assert self.watcher is not None
        ready = self.watcher.poll(time.monotonic())
        if ready:
            self.get_logger().info(f"new forecast files: {[str(p) for p in ready]}")
            self.requests.put(LoadRequest([str(p) for p in ready], "watch_dir"))

    def _on_load(self, request: LoadForecast.Request,
                 response: LoadForecast.Response) -> LoadForecast.Response:
        reason = service_request_error(request)
        if reason is not None:  # refused before any file is read: the last cycle stays
            self._failed(LoadRequest(list(request.paths), "service"), WeatherError(reason))
            response.accepted, response.message = False, reason
            return response
        req = LoadRequest(list(request.paths), "service", threading.Event())
        if request.member_files:
            req.members = member_file_groups(list(request.member_files))
            req.paths = [f for g in req.members for f in g]
            req.labels = tuple(str(x) for x in request.member_labels)
        self.requests.put(req)
        assert req.done is not None
        if not req.done.wait(timeout=120.0):
            response.accepted, response.message = False, "load did not finish within 120 s"
            return response
        response.accepted, response.cycle_id, response.message = req.result
        return response

    def _work(self) -> None:
        while True:
            req = self.requests.get()
            if req is None:
                return
            req.result = self._load(req)
            if req.done is not None:
                req.done.set()

    def _load(self, req: LoadRequest) -> tuple[bool, str, str]:
        t0 = time.monotonic()
        publication = f"{self.session}-{self.loads + 1}"
        encoding = str(self.get_parameter("slice_encoding").value)
        spool: SliceSpool | None = None
        try:
            if not req.paths:
                raise WeatherError("no paths given")
            # the whole cycle is encoded (to the spool file) before it is announced: a failure
            # leaves the last good cycle in force, and the announcement is followed by slices
            # at the transport's pace (no encoding sits in between)
            cfg = (self.cfg_base if req.labels is None
                   else replace(self.cfg_base, member_labels=req.labels))
            spool = SliceSpool(self.spool_dir)
            info, sizes, notes, how = load_cycle(
                req.paths, cfg, req.members or (),
                lambda s: spool_slice(spool, slice_to_msg(s, None, encoding), publication))
            nbytes, total_bytes = max(sizes, default=0), sum(sizes)
            budget = wire_summary(info, total_bytes, nbytes, encoding, cfg)
            cycle = cycle_to_msg(info)
        except Exception as exc:  # a bad file must never stop the node
            if spool is not None:
                spool.close()
            return self._failed(req, exc)
        self.loads += 1
        cycle.publication_id = publication
        try:
            self._publish_cycle(cycle, spool)
        except Exception as exc:  # e.g. the spool file unreadable: the node keeps serving
            spool.close()
            return self._failed(req, WeatherError(f"cycle {info.cycle_id} publication "
                                                  f"{publication} not completed: {exc}"))
        dt = time.monotonic() - t0
        with self.lock:
            n = int(self.state["cycles_published"]) + 1
            self.state.update(cycle_id=info.cycle_id, slices=str(info.slice_count),
                              members=str(info.member_count),
                              member_labels=", ".join(info.member_labels),
                              slice_encoding=encoding, bytes_per_slice=str(nbytes),
                              cycle_wire_bytes=str(total_bytes), wire_budget=budget,
                              load_path=how,
                              source_files=", ".join(req.paths),
                              load_s=f"{dt:.3f}", last_error="", notes="; ".join(notes),
                              cycles_published=str(n), publication_id=publication)
            self.level = DiagnosticStatus.WARN if notes else DiagnosticStatus.OK
            self.message = f"serving cycle {info.cycle_id} ({info.slice_count} slices, " \
                           f"{info.member_count} member(s))"
        return_freed_memory()  # the decoded blocks and encoding buffers: back to the OS
        self.get_logger().info(f"published cycle {info.cycle_id}: {info.slice_count} slices "
                               f"of {info.member_count} member(s) "
                               f"({encoding}, {nbytes} B of field values each) in {dt:.2f} s "
                               f"from {req.paths}")
        self._publish_diagnostics()
        return True, info.cycle_id, "; ".join(notes)

    def _publish_cycle(self, cycle: ForecastCycle, spool: SliceSpool) -> None:
        """Announce the cycle, then publish its spooled slices one at a time (each slice's
        bytes live only until the middleware has copied them into its history). The spool is
        kept for re-publication (publish_period_s > 0) or closed."""
        if self.publish_period_s <= 0:
            self._fresh_slice_publisher()
        with self.publish_lock:  # a re-publication of the previous cycle is not interleaved
            cycle.header.stamp = self.get_clock().now().to_msg()  # publication time
            self.cycle_pub.publish(cycle)
            publish_spooled(self.slice_pub, spool, self.get_clock().now().to_msg())
            with self.lock:
                previous = self.current
                self.current = (cycle, spool) if self.publish_period_s > 0 else None
        if previous is not None:
            previous[1].close()
        if self.publish_period_s <= 0:
            spool.close()

    def _fresh_slice_publisher(self) -> None:
        """Replace the slice publisher before a new cycle goes out: its transient-local history
        (up to max_slices slices, 143 MB at 200 storm slices, most of them the old cycle's)
        is freed at once instead of sitting beside the new cycle while it is published, the
        peak of every load. Subscribers match the new writer and get the whole new cycle."""
        old = self.slice_pub
        self.slice_pub = self.create_publisher(ForecastSlice, FORECAST_SLICES,
                                               latched(self.max_slices))
        self.destroy_publisher(old)

    def _failed(self, req: LoadRequest, exc: Exception) -> tuple[bool, str, str]:
        return_freed_memory()
        text = f"{req.origin}: {exc}"
        self.get_logger().error(f"forecast load failed, previous cycle stays in force: {text}")
        with self.lock:
            self.state["last_error"] = text
            self.state["loads_refused"] = str(int(self.state["loads_refused"]) + 1)
            self.state["loads_refused_last_reason"] = text
            self.level = DiagnosticStatus.ERROR
            kept = self.state["cycle_id"] or "none"
            self.message = f"load failed ({exc}); serving cycle {kept}"
        self._publish_diagnostics()
        return False, "", str(exc)

    def _republish(self) -> None:
        with self.publish_lock:  # the spool in force is not closed while it is read
            with self.lock:
                current = self.current
            if current is None:
                return
            try:
                self.cycle_pub.publish(current[0])
                publish_spooled(self.slice_pub, current[1], self.get_clock().now().to_msg())
            except Exception as exc:  # a failed round must not end the node; the next may work
                self.get_logger().error(f"re-publication of cycle {current[0].cycle_id} "
                                        f"failed: {exc}")

    def _publish_diagnostics(self) -> None:
        with self.lock:
            # loads run one at a time in arrival order; the ones behind it wait (none is
            # dropped), so memory never holds two cycles being loaded
            self.state["loads_waiting"] = str(self.requests.qsize())
            self.state.update(resident_memory_mb())
            status = DiagnosticStatus(level=self.level, name=DIAG_NAME, message=self.message,
                                      hardware_id="shiproute_weather",
                                      values=[KeyValue(key=k, value=v)
                                              for k, v in self.state.items()])
        arr = DiagnosticArray(status=[status])
        arr.header.stamp = self.get_clock().now().to_msg()
        try:
            self.diag_pub.publish(arr)
        except RuntimeError as err:  # rclpy's RCLError: a failed sample must not end the node
            self.get_logger().warning(f"diagnostics not published: {err}")

    def stop(self) -> None:
        """Stop the loader thread."""
        self.requests.put(None)
        self.worker.join(timeout=5.0)


def main(argv: list[str] | None = None) -> int:
    """Console script `shiproute_weather_node`; runs until SIGINT/SIGTERM."""
    return_large_blocks_at_once(1 << 15)  # a packed field of a slice is ~55 kB
    warm_array_backends()
    rclpy.init(args=argv if argv is not None else sys.argv)
    node = WeatherNode()
    executor = MultiThreadedExecutor(num_threads=3)
    executor.add_node(node)
    spin_until_shutdown(executor, (node,), stop=(node.stop,))
    return 0


if __name__ == "__main__":
    sys.exit(main())
