"""Benchmark: load + validate + publish one 16-day 3-hourly 0.5 deg North Pacific cycle; a
two-source cycle (wind and waves + currents on another grid and step) loaded and encoded; and
what a 20-member cycle costs within the node's slice budget (`bench_ensemble`)."""

from __future__ import annotations

import argparse
import json
import os
import random
import resource
import subprocess
import sys
import time

from shiproute_core.bench_report import print_figures
from shiproute_core.topics import FORECAST_CYCLE, FORECAST_SLICES

_SUBSCRIBER = r"""
import sys, time, rclpy
from rclpy.qos import QoSProfile, HistoryPolicy, ReliabilityPolicy, DurabilityPolicy
from shiproute_msgs.msg import ForecastSlice, ForecastCycle
rclpy.init()
node = rclpy.create_node("bench_weather_subscriber")
depth = int(sys.argv[1])
qos = lambda d: QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=d,
                           reliability=ReliabilityPolicy.RELIABLE,
                           durability=DurabilityPolicy.TRANSIENT_LOCAL)
got = {}
cycle = []
node.create_subscription(ForecastSlice, sys.argv[3],
                         lambda m: got.__setitem__(m.slice_index, m.slice_count), qos(depth))
node.create_subscription(ForecastCycle, sys.argv[2], cycle.append, qos(1))
print("ready", flush=True)
while rclpy.ok():
    rclpy.spin_once(node, timeout_sec=0.05)
    if cycle and len(got) == cycle[-1].slice_count:
        print(f"received {len(got)} {time.time():.6f}", flush=True)
        break
node.destroy_node()
rclpy.shutdown()
"""


def _cpu_s() -> float:
    """CPU time of this process (user + system): comparable across machine loads."""
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def _parse(argv: list[str]) -> argparse.Namespace:
    ap = argparse.ArgumentParser(prog="shiproute bench weather", description=__doc__)
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    ap.add_argument("--scenario", default="storm_march", help="bundled scenario to publish")
    ap.add_argument("--file", default="", help="forecast file instead of a scenario")
    ap.add_argument("--timeout-s", type=float, default=120.0)
    ap.add_argument("--encoding", default="", help="slice field encoding (default: the weather "
                    "node's default)")
    return ap.parse_args(argv)


def main(argv: list[str] | None = None) -> int:
    """Entry point of `shiproute bench weather`."""
    args = _parse(sys.argv[1:] if argv is None else argv)
    from ..scenarios.catalogue import scenario_path

    path = args.file or str(scenario_path(args.scenario))  # generation is not timed
    domain = random.Random().randint(0, 101)
    env = {**os.environ, "ROS_DOMAIN_ID": str(domain),
           "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST"}
    os.environ.update({k: env[k] for k in ("ROS_DOMAIN_ID", "ROS_AUTOMATIC_DISCOVERY_RANGE")})
    sub = subprocess.Popen([sys.executable, "-u", "-c", _SUBSCRIBER, "200", FORECAST_CYCLE,
                            FORECAST_SLICES], env=env,
                           stdout=subprocess.PIPE, text=True, start_new_session=True)
    try:
        assert sub.stdout is not None
        if "ready" not in sub.stdout.readline():
            raise RuntimeError("benchmark subscriber did not start")
        result = _run(path, sub, args.timeout_s, args.encoding)
    finally:
        if sub.poll() is None:
            sub.terminate()
            sub.wait(timeout=10)
    if not args.file:  # the two-source cycle, in its own process (its own memory peak)
        from .bench_multi import make_sources

        make_sources(args.scenario)  # derived files are made once, not timed
        out = subprocess.run([sys.executable, "-m", "shiproute_weather.experiments.bench_multi"],
                             capture_output=True, text=True, timeout=args.timeout_s, env=env)
        if out.returncode != 0:
            raise RuntimeError(f"two-source benchmark failed: {out.stderr[-2000:]}")
        result.update(json.loads(out.stdout.strip().splitlines()[-1]))
        ens = subprocess.run([sys.executable, "-m",
                              "shiproute_weather.experiments.bench_ensemble"],
                             capture_output=True, text=True, timeout=args.timeout_s, env=env)
        if ens.returncode != 0:
            raise RuntimeError(f"ensemble budget benchmark failed: {ens.stderr[-2000:]}")
        result.update(json.loads(ens.stdout.strip().splitlines()[-1]))
    print_figures(result, args.json)
    return 0


def _run(path: str, sub: subprocess.Popen[str], timeout_s: float,
         encoding: str) -> dict:
    import rclpy

    from shiproute_msgs.msg import ForecastCycle, ForecastSlice

    from ..ingest.cycle_builder import CycleConfig, build_cycle
    from ..ingest.stream import load_encoded, streamable, warm_array_backends
    from ..ros.convert import DEFAULT_SLICE_ENCODING, cycle_to_msg, slice_to_msg, wire_bytes
    from ..ros.node import latched

    rclpy.init()
    node = rclpy.create_node("bench_weather_publisher")
    cyc_pub = node.create_publisher(ForecastCycle, FORECAST_CYCLE, latched(1))
    sl_pub = node.create_publisher(ForecastSlice, FORECAST_SLICES, latched(200))
    deadline = time.monotonic() + 30.0
    while sl_pub.get_subscription_count() == 0 and time.monotonic() < deadline:
        time.sleep(0.05)
    cfg = CycleConfig()
    encoding = encoding or DEFAULT_SLICE_ENCODING
    warm_array_backends()  # as the node does at start
    c0 = _cpu_s()
    t0 = time.perf_counter()
    msgs: list[ForecastSlice]  # encoded whole before the announcement, as the node does
    if streamable([path], cfg):  # what the node does for one NetCDF file
        info, msgs, _ = load_encoded(path, cfg, lambda s: slice_to_msg(s, encoding=encoding))
    else:
        info, slices, _ = build_cycle([path], cfg)
        msgs = []
        for k in range(len(slices)):
            s, slices[k] = slices[k], None  # type: ignore[call-overload]  # free as we go
            msgs.append(slice_to_msg(s, encoding=encoding))
            del s
    t1 = time.perf_counter()
    c1 = _cpu_s()
    sent_bytes = max((wire_bytes(m) for m in msgs), default=0)
    n = len(msgs)
    cyc_pub.publish(cycle_to_msg(info))
    for m in msgs:
        sl_pub.publish(m)
    t2 = time.perf_counter()
    c2 = _cpu_s()
    wall_sent = time.time()
    assert sub.stdout is not None
    line = sub.stdout.readline()
    delivered_s = float(line.split()[2]) - wall_sent + (t2 - t1) if line.startswith(
        "received") else float("nan")
    rss_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    node.destroy_node()
    rclpy.try_shutdown()
    return {"file": os.path.basename(path), "load_s": round(t1 - t0, 3),
            "publish_s": round(t2 - t1, 3), "delivered_s": round(delivered_s, 3),
            "total_s": round(t2 - t0, 3), "load_cpu_s": round(c1 - c0, 3),
            "publish_cpu_s": round(c2 - c1, 3), "slices": n, "encoding": encoding,
            "bytes_per_slice": sent_bytes,
            "fields": len(info.fields), "peak_rss_mb": round(rss_mb, 1)}
