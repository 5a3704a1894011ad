"""Benchmark `shiproute bench soak`: weather and planner nodes under repeated forecast cycles.

The weather and planner nodes run as separate processes; this process plays the ship
(ShipState at 10 Hz) and the forecast office: every `--period` seconds (2 s; the next load is
sent once the previous one has been answered) it asks the weather node to load the March storm
forecast's two real cycles in turn (`storm_march`, `storm_march_cycle2`), and every 30 s it
publishes a bad cycle (zero longitude spacing) of its own, which the planner must refuse. The
planner runs with `accept_older_forecasts:=true` because the two cycles alternate (every other
one is an older model run). Reported: loads answered (`cycles`), plans received, cycles the
planner refused or dropped incomplete (`rejected`), node deaths, and each node's resident
memory at the start (after a warm-up of 30 s, both cycles loaded, then 8 s without a load),
at the end (8 s after the last load) and its peak (VmHWM) over the whole run.
"""

from __future__ import annotations

import argparse
import array
import sys
import time
from typing import Any

from shiproute_core.bench_report import print_figures

from shiproute_bringup.bench_nodes import BenchPeer, peak_rss_mb, rss_mb, start_nodes
from shiproute_bringup.rosproc import random_domain_id
from shiproute_core import topics

DEPART_S = 1772560800.0  # 2026-03-03T18:00:00Z, the storm scenario's departure
RTA = "2026-03-16T18:00:00Z"
BUSAN = (35.08, 129.112)
WARMUP_S = 30.0
QUIET_S = 8.0  # no load for this long before start and end are measured
BAD_EVERY_S = 30.0
#: the first plan includes the planner's start-up (compiled kernels, land and depth data): on a
#: machine shared by several sessions it took over 120 s
FIRST_PLAN_S = 300.0


def _bad_cycle(types: dict, k: int) -> tuple:
    """A one-slice cycle with zero longitude spacing (used to make every plan divide by zero)."""
    cycle_t, slice_t, field_t = types["ForecastCycle"], types["ForecastSlice"], types["Field"]
    cid = f"soak-bad-{k}"
    c = cycle_t(cycle_id=cid, slice_count=1)
    c.reference_time.sec = int(DEPART_S)
    s = slice_t(cycle_id=cid, slice_index=0, slice_count=1, lat0_deg=10.0, dlat_deg=5.0,
                n_lat=11, lon0_deg=115.0, dlon_deg=0.0, n_lon=27)
    s.reference_time.sec = s.valid_time.sec = int(DEPART_S)
    s.fields = [field_t(name=n, units="m s-1", data=array.array("f", [1.0] * 297))
                for n in ("eastward_wind", "northward_wind")]
    return c, s


def run(minutes: float, period_s: float, budget_s: float) -> dict:
    """Start the nodes, soak them for `minutes`, return the figures."""
    from diagnostic_msgs.msg import DiagnosticArray
    from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
    from shiproute_weather.scenarios.catalogue import scenario_path

    from shiproute_msgs.msg import (
        ForecastCycle,
        ForecastField,
        ForecastSlice,
        RoutePlan,
        ShipState,
    )
    from shiproute_msgs.srv import LoadForecast

    files = [str(scenario_path("storm_march")), str(scenario_path("storm_march_cycle2"))]
    dom = random_domain_id()
    weather, planner = start_nodes(
        dom, [f"forecast_files:=['{files[0]}']"], RTA, budget_s,
        ["accept_older_forecasts:=true", "write_png:=false"])
    procs = {"weather": weather, "planner": planner}
    peer = BenchPeer("bench_soak", dom)
    node, latched = peer.node, peer.latched
    plans: list[str] = []
    diag: dict[str, str] = {}

    def on_diag(msg: DiagnosticArray) -> None:
        for st in msg.status:
            if st.name == "shiproute_planner":
                diag.update({kv.key: kv.value for kv in st.values})

    node.create_subscription(RoutePlan, topics.PLAN_ROUTE,
                             lambda m: plans.append(m.cycle_id), latched)
    node.create_subscription(DiagnosticArray, topics.DIAGNOSTICS, on_diag, 10)
    state_pub = node.create_publisher(ShipState, topics.SHIP_STATE, 10)
    cycle_pub = node.create_publisher(ForecastCycle, topics.FORECAST_CYCLE, latched)
    slice_pub = node.create_publisher(ForecastSlice, topics.FORECAST_SLICES, QoSProfile(
        depth=512, reliability=ReliabilityPolicy.RELIABLE,
        durability=DurabilityPolicy.TRANSIENT_LOCAL))
    load: Any = node.create_client(LoadForecast, topics.FORECAST_LOAD)
    types = {"ForecastCycle": ForecastCycle, "ForecastSlice": ForecastSlice,
             "Field": ForecastField}

    cycles = refused_loads = bad_sent = deaths = 0
    start_rss: dict[str, float] = {}
    pending = None
    next_load = next_bad = next_state = 0.0
    t_start = time.monotonic()
    try:
        deadline = time.monotonic() + FIRST_PLAN_S
        while not plans:  # the first plan on the initial cycle
            if time.monotonic() > deadline:
                raise TimeoutError(f"no first plan within {FIRST_PLAN_S:.0f} s")
            if time.monotonic() >= next_state:
                state_pub.publish(_state(ShipState))
                next_state = time.monotonic() + 0.1
            peer.spin_once(0.02)
        t_start = time.monotonic()
        end = t_start + minutes * 60.0
        next_bad = t_start + BAD_EVERY_S
        quiet_since = 0.0
        while time.monotonic() < end:
            now = time.monotonic()
            if now >= next_state:
                state_pub.publish(_state(ShipState))
                next_state = now + 0.1
            if not start_rss and now - t_start >= WARMUP_S:  # no loads for QUIET_S, measure
                quiet_since = quiet_since or (now if pending is None else 0.0)
                if quiet_since and now - quiet_since >= QUIET_S:
                    start_rss = {k: rss_mb(p.proc.pid) for k, p in procs.items()}
                    end += now - (t_start + WARMUP_S)  # the pause does not count
            elif (pending is None and now >= next_load and load.service_is_ready()
                  and now < end - QUIET_S):
                req = LoadForecast.Request(paths=[files[(cycles + refused_loads + 1) % 2]])
                pending = load.call_async(req)
                next_load = now + period_s
            if pending is not None and pending.done():
                ans = pending.result()
                if ans is not None and ans.accepted:
                    cycles += 1
                else:
                    refused_loads += 1
                pending = None
            if now >= next_bad:
                c, s = _bad_cycle(types, bad_sent)
                cycle_pub.publish(c)
                slice_pub.publish(s)
                bad_sent += 1
                next_bad = now + BAD_EVERY_S
            dead = [name for name, p in procs.items() if not p.running()]
            if dead:  # reported, with the node's last output on stderr
                deaths = len(dead)
                for name in dead:
                    print(f"[soak] {name} died:\n{procs[name].output[-3000:]}", file=sys.stderr)
                break
            peer.spin_once(0.01)
        while pending is not None and not pending.done():  # the last load's answer
            peer.spin_once(0.05)
        t_quiet = time.monotonic() + 2.0  # the last load was sent >= QUIET_S before `end`
        while time.monotonic() < t_quiet:
            if time.monotonic() >= next_state:
                state_pub.publish(_state(ShipState))
                next_state = time.monotonic() + 0.1
            peer.spin_once(0.05)
        end_rss = {k: rss_mb(p.proc.pid) for k, p in procs.items()}
        peak = {k: peak_rss_mb(p.proc.pid) for k, p in procs.items()}
    finally:
        peer.close()
        planner.stop()
        weather.stop()
    return {
        "minutes": round((time.monotonic() - t_start) / 60.0, 2), "period_s": period_s,
        "cycles": cycles, "loads_refused": refused_loads,
        "cycles_accepted_by_planner": int(diag.get("forecast_cycles_accepted", "0")),
        "plans": len(plans), "plans_failed": int(diag.get("plans_failed", "0")),
        "bad_cycles_sent": bad_sent,
        "rejected": int(diag.get("forecast_cycles_dropped", "0")),
        "rejected_last_reason": diag.get("forecast_cycles_last_reason", ""),
        "ship_states_dropped": int(diag.get("ship_states_dropped", "0")),
        "node_deaths": deaths,
        **{f"{k}_rss_mb_{w}": round(v[k], 1) for k in ("weather", "planner")
           for w, v in (("start", start_rss), ("end", end_rss), ("peak", peak))},
    }


def _state(ship_state_type) -> object:
    msg = ship_state_type()
    msg.header.stamp.sec = int(DEPART_S)
    msg.latitude_deg, msg.longitude_deg = BUSAN
    msg.sog_kn, msg.cog_deg, msg.heading_deg = 0.0, 90.0, 90.0
    return msg


def main(argv: list[str] | None = None) -> int:
    """Entry point of `shiproute bench soak`."""
    p = argparse.ArgumentParser(prog="shiproute bench soak", description=__doc__.splitlines()[0])
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--minutes", type=float, default=10.0, help="soak duration [min]")
    p.add_argument("--period", type=float, default=2.0, help="seconds between forecast loads")
    p.add_argument("--budget", type=float, default=0.5, help="planner budget per plan [s]")
    args = p.parse_args(argv)
    if not (args.minutes > 0 and args.period > 0 and args.budget > 0):
        p.error("--minutes, --period and --budget must be positive")
    result = run(args.minutes, args.period, args.budget)
    print_figures(result, args.json)
    return 0

