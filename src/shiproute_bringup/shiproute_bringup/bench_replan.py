"""Benchmark `shiproute bench replan`: new ForecastCycle -> new RoutePlan latency across processes.

The weather and planner nodes run as separate processes; this process plays the ship and the
integrator. After the first plan, five new forecast cycles (the March storm's second cycle,
each written with its own cycle id) are dropped into the watched directory one at a time; the
latency is measured from the ForecastCycle's publication (its header stamp: the weather node
stamps it with the wall clock just before publishing, and all processes share this host's
clock) to the RoutePlan on that cycle arriving here. `planner_rss_mb` is the planner's resident
memory when the last plan arrives, `planner_peak_rss_mb` its high-water mark over the run (both
cycles alive during a change included). `--log` prints the nodes' logs (with the planner's
per-cycle reception and planning times) on stderr.
"""

from __future__ import annotations

import argparse
import shutil
import statistics
import tempfile
import time
from pathlib import Path

from shiproute_core.bench_report import print_figures

from shiproute_bringup.bench_nodes import BenchPeer, peak_rss_mb, rss_mb, start_nodes
from shiproute_bringup.rosproc import RosProcess, random_bench_domain_id
from shiproute_core import topics

DEPART_S = 1772560800.0  # 2026-03-03T18:00:00Z
RTA = "2026-03-16T18:00:00Z"


def _cycle_files(work: Path, n: int) -> list[Path]:
    from shiproute_weather.scenarios.catalogue import scenario_dataset

    ds = scenario_dataset("storm_march_cycle2")
    out = []
    for k in range(n):
        copy = ds.copy()
        copy.attrs["cycle_id"] = f"bench-cycle-{k + 1}"
        path = work / f"cycle_{k + 1}.nc"
        copy.to_netcdf(path)
        out.append(path)
    return out


def run(budget_s: float, repeats: int, log: bool = False) -> dict:
    """Start the nodes, measure `repeats` re-plans, return the figures."""
    from shiproute_weather.scenarios.catalogue import scenario_path

    from shiproute_msgs.msg import ForecastCycle, RoutePlan, ShipState

    dom = random_bench_domain_id()
    work = Path(tempfile.mkdtemp(prefix="shiproute-bench-replan-"))
    watch = work / "watch"
    watch.mkdir()
    (watch / "storm_march.nc").symlink_to(scenario_path("storm_march"))
    files = _cycle_files(work, repeats)
    weather, planner = start_nodes(
        dom, [f"watch_dir:={watch}", "watch_period_s:=0.1", "settle_s:=0.1"], RTA, budget_s,
        [f"seed_pool_dir:={work / 'pool'}"])
    peer = BenchPeer("bench_replan", dom)
    node, latched = peer.node, peer.latched
    cycles: dict[str, float] = {}  # cycle id -> publication stamp [POSIX s]
    plans: dict[str, float] = {}

    def on_cycle(msg: ForecastCycle) -> None:
        cycles.setdefault(msg.cycle_id, _stamp_s(msg))

    def on_plan(msg: RoutePlan) -> None:
        plans.setdefault(msg.cycle_id, time.time())

    node.create_subscription(ForecastCycle, topics.FORECAST_CYCLE, on_cycle, latched)
    node.create_subscription(RoutePlan, topics.PLAN_ROUTE, on_plan, latched)
    pub = node.create_publisher(ShipState, topics.SHIP_STATE, 10)

    def spin_until(pred, timeout_s: float, what: str) -> None:
        deadline = time.monotonic() + timeout_s
        next_state = 0.0
        while not pred():
            if time.monotonic() > deadline:
                raise TimeoutError(f"{what} not within {timeout_s} s")
            if time.monotonic() >= next_state:
                msg = ShipState()
                msg.header.stamp.sec = int(DEPART_S)
                msg.latitude_deg, msg.longitude_deg = 35.08, 129.112
                pub.publish(msg)
                next_state = time.monotonic() + 0.5
            peer.spin_once(0.02)

    latencies = []
    try:
        spin_until(lambda: plans, 120, "first plan")
        for k, path in enumerate(files):
            cid = f"bench-cycle-{k + 1}"
            (watch / path.name).symlink_to(path)
            spin_until(lambda c=cid: c in plans and c in cycles, 60 + 5 * budget_s,
                       f"plan on {cid}")
            latencies.append(plans[cid] - cycles[cid])
        rss = rss_mb(planner.proc.pid)
        peak = peak_rss_mb(planner.proc.pid)
    finally:
        if log:
            _print_logs(weather, planner, cycles, plans)
        peer.close()
        planner.stop()
        weather.stop()
        shutil.rmtree(work, ignore_errors=True)  # the cycle copies: ~180 MB each
    return {"replan_latency_s": round(statistics.median(latencies), 3),
            "replan_latencies_s": [round(x, 3) for x in latencies],
            "planner_budget_s": budget_s, "planner_rss_mb": round(rss, 1),
            "planner_peak_rss_mb": round(peak, 1)}


def _stamp_s(msg) -> float:
    """Header stamp of a message as POSIX seconds."""
    return msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9


def _print_logs(weather: RosProcess, planner: RosProcess, cycles: dict[str, float],
                plans: dict[str, float]) -> None:
    """The nodes' log lines, cycle stamps and plan arrival times (wall clock) on stderr."""
    import sys

    for name, proc in (("weather", weather), ("planner", planner)):
        for line in proc.lines:
            print(f"[{name}] {line}", file=sys.stderr)
    for what, arrivals in (("cycle", cycles), ("plan", plans)):
        for cid, t in arrivals.items():
            print(f"[bench] {what} {cid} at {t:.3f}", file=sys.stderr)


def main(argv: list[str] | None = None) -> int:
    """Entry point of `shiproute bench replan`."""
    p = argparse.ArgumentParser(prog="shiproute bench replan", description=__doc__.splitlines()[0])
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--budget", type=float, default=0.5, help="planner budget per plan [s]")
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--log", action="store_true", help="print the nodes' logs on stderr")
    args = p.parse_args(argv)
    result = run(args.budget, args.repeats, args.log)
    print_figures(result, args.json)
    return 0
