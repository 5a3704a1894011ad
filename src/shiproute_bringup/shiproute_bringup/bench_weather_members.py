"""Benchmark the weather node on the 20-member ensemble: memory and wire cost per cycle.

A real weather node process starts on the bundled `storm_march_ensemble` (20 members, 1 deg,
6-hourly, 16 days; streamed member by member and block by block) and then, through its
LoadForecast service, alternates the deterministic `storm_march` cycle (0.5 deg, 3-hourly)
with the ensemble `--rounds` times. Reported: the ensemble cycle's members, slices and bytes of
field values on the wire (`cycle_bytes`) as the node's diagnostics state them, the load time of
each kind, and the node's resident memory: `weather_rss_peak_mb` (VmHWM over the run, target
<= 400 MB as issue #16 asks of the weather node), `weather_rss_end_mb`, and the peak so far
after each load (`rss_peak_after_mb`: which load set it).
"""

from __future__ import annotations

import argparse
import sys
import time
from typing import Any

from shiproute_core.bench_report import print_figures

from shiproute_core import topics

TARGETS = {"weather_rss_peak_mb": 400.0}
DIAG_NAME = "shiproute_weather: forecast"


def _load(peer: Any, cli: Any, paths: list[str]) -> tuple[float, str]:
    """(seconds, cycle id) of one LoadForecast call."""
    from shiproute_msgs.srv import LoadForecast

    t0 = time.monotonic()
    fut = cli.call_async(LoadForecast.Request(paths=paths))
    while not fut.done():
        peer.spin_once(0.05)
        if time.monotonic() - t0 > 300:
            raise RuntimeError(f"LoadForecast {paths} did not answer within 300 s")
    res = fut.result()
    if not res.accepted:
        raise RuntimeError(f"LoadForecast {paths} refused: {res.message}")
    return time.monotonic() - t0, str(res.cycle_id)


def run(rounds: int, control: bool = False, max_slices: int = 200) -> dict[str, Any]:
    """Start the node, alternate the cycles, read the diagnostics and memory."""
    from diagnostic_msgs.msg import DiagnosticArray
    from shiproute_weather.scenarios.catalogue import scenario_path

    from shiproute_bringup.bench_nodes import BenchPeer, peak_rss_mb, rss_mb
    from shiproute_bringup.rosproc import RosProcess, console_script, random_bench_domain_id
    from shiproute_msgs.srv import LoadForecast

    ensemble = str(scenario_path("storm_march_cycle2" if control else "storm_march_ensemble"))
    deterministic = str(scenario_path("storm_march"))
    dom = random_bench_domain_id()
    diag: dict[str, dict[str, str]] = {}
    with RosProcess([console_script("shiproute_weather_node"), "--ros-args", "-p",
                     f"forecast_files:=['{ensemble}']", "-p", f"max_slices:={max_slices}"],
                    domain_id=dom,
                    name="weather") as weather:
        peer = BenchPeer("bench_weather_members", dom)
        try:
            def on_diag(msg: DiagnosticArray) -> None:
                for s in msg.status:
                    if s.name == DIAG_NAME:
                        diag[s.name] = {kv.key: kv.value for kv in s.values}

            peer.node.create_subscription(DiagnosticArray, topics.DIAGNOSTICS, on_diag, 10)
            cli: Any = peer.node.create_client(LoadForecast, topics.FORECAST_LOAD)
            weather.wait_for_line(r"published cycle \S+: \d+ slices of \d+ member", 300)
            rss_start = rss_mb(weather.proc.pid)
            steps = [["start-up ensemble", round(peak_rss_mb(weather.proc.pid), 1)]]
            loads: dict[str, list[float]] = {"ensemble": [], "deterministic": []}
            figures: dict[str, str] = {}
            for _ in range(rounds):
                for kind, path in (("deterministic", deterministic), ("ensemble", ensemble)):
                    dt, cycle_id = _load(peer, cli, [path])
                    loads[kind].append(dt)
                    t_end = time.monotonic() + 10
                    while diag.get(DIAG_NAME, {}).get("cycle_id") != cycle_id \
                            and time.monotonic() < t_end:
                        peer.spin_once(0.05)
                    if kind == "ensemble":
                        figures = dict(diag.get(DIAG_NAME, {}))
                    steps.append([kind, round(peak_rss_mb(weather.proc.pid), 1)])
            return {
                "members": int(figures.get("members", 0)),
                "slices": int(figures.get("slices", 0)),
                "cycle_bytes": int(figures.get("cycle_wire_bytes", 0)),
                "slice_bytes": int(figures.get("bytes_per_slice", 0)),
                "load_path": figures.get("load_path", ""),
                "wire_budget": figures.get("wire_budget", ""),
                "ensemble_load_s": round(max(loads["ensemble"]), 2),
                "deterministic_load_s": round(max(loads["deterministic"]), 2),
                "rounds": rounds,
                "weather_rss_start_mb": round(rss_start, 1),
                "weather_rss_end_mb": round(rss_mb(weather.proc.pid), 1),
                "weather_rss_peak_mb": round(peak_rss_mb(weather.proc.pid), 1),
                "rss_peak_after_mb": steps,  # VmHWM after each load: which load set the peak
                "targets": TARGETS,
            }
        finally:
            peer.close()


def main(argv: list[str] | None = None) -> int:
    """Entry point of `shiproute bench weather-members`."""
    p = argparse.ArgumentParser(prog="shiproute bench weather-members",
                                description=(__doc__ or "").splitlines()[0])
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--rounds", type=int, default=3,
                   help="deterministic + ensemble loads after the start-up load")
    p.add_argument("--control", action="store_true",
                   help="alternate two deterministic cycles instead (storm_march_cycle2 in "
                        "the ensemble's place): the node's memory without members")
    p.add_argument("--max-slices", type=int, default=200, help="the node's max_slices")
    args = p.parse_args(argv)
    print_figures(run(args.rounds, args.control, args.max_slices), args.json)
    sys.stdout.flush()
    return 0
