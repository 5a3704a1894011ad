"""Run the end-to-end demo: replay Busan -> Long Beach on sim time, plan, re-plan on a new cycle.

The weather, replay, planner and bridge display nodes run as separate processes under
`shiproute bringup`, a recorder writes every topic to MCAP, and this process watches the plans:
the page's URL, one line per plan, then it drops the next forecast cycle into the weather node's
watched directory part-way through the voyage and finishes once the re-plan on that cycle has
arrived (or, with --keep-open, keeps everything running until Ctrl-C).
"""

from __future__ import annotations

import argparse
import re
import shutil
import sys
import time
from datetime import UTC, datetime
from pathlib import Path

import yaml

from shiproute_bringup import demo_data
from shiproute_bringup.rosproc import RosProcess, console_script
from shiproute_core import topics


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="shiproute demo", description=__doc__.splitlines()[0])
    p.add_argument("--out", help="output directory (default: ./shiproute_out/demo-<UTC time>)")
    p.add_argument("--rate", type=float, default=3000.0, help="replay speed-up over real time")
    p.add_argument("--budget", type=float, default=3.0, help="planner budget per plan [s]")
    p.add_argument("--second-cycle-after-h", type=float, default=12.0,
                   help="sim hours after departure when the next forecast cycle appears")
    p.add_argument("--timeout", type=float, default=110.0, help="give up after this [s]")
    p.add_argument("--display-port", type=int, default=8765,
                   help="port of the bridge display page on 127.0.0.1 (0: any free port)")
    p.add_argument("--no-display", action="store_true", help="run without the bridge display")
    p.add_argument("--keep-open", action="store_true",
                   help="after the re-plan keep every node (and the page) running until Ctrl-C")
    return p


def _params(args: argparse.Namespace, data: demo_data.DemoData, out: Path) -> dict:
    watch = out / "forecasts"
    return {
        "common_parameters": {"use_sim_time": True},
        "nodes": [
            {"name": "shiproute_weather", "executable": "shiproute_weather_node",
             "parameters": {"watch_dir": str(watch), "watch_period_s": 0.5,
                            "settle_s": 0.5}},
            {"name": "shiproute_replay", "executable": "shiproute_replay_node",
             "parameters": {"bag": str(data.voyage_bag), "rate": float(args.rate),
                            "publish_clock": True, "start_paused": False}},
            {"name": "shiproute_planner", "executable": "shiproute_planner_node",
             "required": True,
             "parameters": {"origin": demo_data.ORIGIN, "destination": demo_data.DESTINATION,
                            "rta": demo_data.RTA, "ship": demo_data.SHIP,
                            "budget_s": float(args.budget), "output_dir": str(out / "plans"),
                            "seed_pool_dir": str(out / "seed_pool"),
                            # The recorded voyage sailed its own route, not our plan: re-plan on
                            # forecast cycles here, not on every departure from the plan.
                            "replan_cross_track_nm": 1000.0, "replan_schedule_h": 72.0}},
        ] + ([] if args.no_display else [
            {"name": "shiproute_display", "executable": "shiproute_display_node",
             "parameters": {"port": int(args.display_port), "bind_address": "127.0.0.1"}},
        ]),
    }


class _Watcher:
    """In-process rclpy subscriber of plans and /clock (plain wall-time node)."""

    def __init__(self) -> None:
        import rclpy
        from rclpy.qos import (
            DurabilityPolicy,
            QoSProfile,
            ReliabilityPolicy,
            qos_profile_sensor_data,
        )
        from rosgraph_msgs.msg import Clock

        from shiproute_msgs.msg import RoutePlan

        rclpy.init(args=[])
        self.node = rclpy.create_node("shiproute_demo_watch")
        latched = QoSProfile(depth=5, reliability=ReliabilityPolicy.RELIABLE,
                             durability=DurabilityPolicy.TRANSIENT_LOCAL)
        self.plans: list = []
        self.clock_s = 0.0
        self.node.create_subscription(RoutePlan, topics.PLAN_ROUTE,
                                      self.plans.append, latched)
        self.node.create_subscription(
            Clock, "/clock",
            lambda m: setattr(self, "clock_s", m.clock.sec + m.clock.nanosec * 1e-9),
            qos_profile_sensor_data)

    def spin_for(self, seconds: float) -> None:
        import rclpy

        rclpy.spin_once(self.node, timeout_sec=seconds)

    def close(self) -> None:
        import rclpy

        self.node.destroy_node()
        rclpy.try_shutdown()


class _PageWatch:
    """Finds the bridge display's URL (or its failure) in the node output and says it once."""

    _URL = re.compile(r"\[shiproute_display\].*bridge display on (http://\S+)")

    def __init__(self) -> None:
        self.url = ""
        self.failure = ""
        self._said = False

    def see(self, line: str) -> None:
        m = self._URL.search(line)
        if m:
            self.url = m.group(1)
        elif "[shiproute_display]" in line and ("rror" in line or "display_node:" in line):
            self.failure = line

    def report(self) -> None:
        if self._said:
            return
        if self.url:
            print(f"bridge display: {self.url} (open it in a browser; live while the demo runs)",
                  flush=True)
            self._said = True
        elif self.failure:
            print(f"bridge display not available: {self.failure}", flush=True)
            self._said = True


def _line(msg, t0: float) -> str:
    def iso(t) -> str:
        return datetime.fromtimestamp(t.sec, UTC).strftime("%m-%d %H:%M")

    eta_h = (msg.eta.sec - msg.rta.sec) / 3600.0
    saved = msg.baseline_fuel_t - msg.total_fuel_t
    pct = 100.0 * saved / msg.baseline_fuel_t if msg.baseline_fuel_t else float("nan")
    return (f"plan {msg.plan_id}  cycle {msg.cycle_id:<24} fuel {msg.total_fuel_t:7.1f} t  "
            f"ETA {iso(msg.eta)} ({eta_h:+.1f} h vs RTA {iso(msg.rta)})  saved "
            f"{saved:+.1f} t ({pct:+.1f} %) vs constant RPM{_infeasible_baseline(msg)}  "
            f"compute {msg.compute_time_s:.2f} s"
            f"  feasible={msg.feasible}  [{time.monotonic() - t0:.0f} s]")


def _infeasible_baseline(msg) -> str:
    """' (infeasible)' when the plan's constant-RPM baseline breaks a constraint."""
    return "" if msg.baseline_feasible else " (infeasible)"


def _replan_words(msg) -> list[str]:
    """What a plan says about its search, the previous plan (kept, or a short search) and
    its arrival time (re-timed, or why not)."""
    return [w for w in msg.warnings
            if w.startswith(("kept previous plan", "search: ", "re-timed: ", "not re-timed: "))]


def main(argv: list[str] | None = None) -> int:
    """Entry point of `shiproute demo`."""
    args = _parser().parse_args(argv)
    t0 = time.monotonic()
    stamp = datetime.now(UTC).strftime("%Y%m%dT%H%M%SZ")
    out = Path(args.out or Path.cwd() / "shiproute_out" / f"demo-{stamp}").resolve()
    (out / "forecasts").mkdir(parents=True, exist_ok=True)
    print(f"demo output directory: {out}", flush=True)
    data = demo_data.prepare(log=lambda s: print(s, flush=True))
    t0 = time.monotonic()  # the demo proper starts once its data exist (made once, cached)
    shutil.copy(data.first_forecast, out / "forecasts" / data.first_forecast.name)
    params = out / "bringup.yaml"
    params.write_text(yaml.safe_dump(_params(args, data, out), sort_keys=False))
    log = (out / "nodes.log").open("w")
    page = _PageWatch()

    def node_line(_stream: str, line: str) -> None:
        log.write(line + "\n")
        page.see(line)

    bringup = RosProcess([console_script("shiproute"), "bringup", str(params)], name="bringup",
                         on_line=node_line)
    def record_line(_stream: str, line: str) -> None:
        log.write("[record] " + line + "\n")

    record = RosProcess([console_script("shiproute"), "bag", "record", str(out / "recording")],
                        name="record", on_line=record_line)
    watcher = _Watcher()
    depart_s = datetime.fromisoformat(demo_data.DEPARTURE.replace("Z", "+00:00")).timestamp()
    second_dropped = False
    seen = 0
    ok = False
    try:
        while time.monotonic() - t0 < args.timeout:
            watcher.spin_for(0.1)
            page.report()
            while seen < len(watcher.plans):
                print(_line(watcher.plans[seen], t0), flush=True)
                for said in _replan_words(watcher.plans[seen]):
                    print(f"    {said}", flush=True)
                seen += 1
            if not bringup.running():
                print("bringup stopped early; see nodes.log", file=sys.stderr)
                break
            passed_h = (watcher.clock_s - depart_s) / 3600.0
            if seen >= 1 and not second_dropped and passed_h >= args.second_cycle_after_h:
                shutil.copy(data.second_forecast, out / "forecasts" / data.second_forecast.name)
                print(f"new forecast cycle dropped at sim {passed_h:.1f} h after departure",
                      flush=True)
                second_dropped = True
            cycles = {p.cycle_id for p in watcher.plans}
            if second_dropped and len(cycles) >= 2:
                ok = True
                break
        if ok and args.keep_open and bringup.running():
            from rclpy.executors import ExternalShutdownException

            print(f"re-plan done; the nodes and the bridge display ({page.url or 'not running'})"
                  " stay up until Ctrl-C", flush=True)
            try:
                while bringup.running():
                    watcher.spin_for(0.2)
                    while seen < len(watcher.plans):
                        print(_line(watcher.plans[seen], t0), flush=True)
                        seen += 1
            except (KeyboardInterrupt, ExternalShutdownException):  # Ctrl-C, as rclpy reports it
                print("stopping", flush=True)
    finally:
        watcher.close()
        record.stop()
        bringup.stop()
        log.close()
    print(f"outputs: {out} (plans/: RTZ, GeoJSON, PNG, JSON; recording/: MCAP of all topics;"
          f" nodes.log) in {time.monotonic() - t0:.0f} s", flush=True)
    if not ok:
        print("demo did not see a plan on the second forecast cycle in time", file=sys.stderr)
        return 1
    return 0
