"""Fleet benchmark: 40 voyages on storm_march at a fixed evaluation budget each (equal work per
voyage, seeds fixed, one planner thread per worker), planned on a 1-worker and a 2-worker
LocalCluster, and one by one in this process for the planning time alone.

Reports the wall time of each batch on workers already set up (forecast loaded, kernels
warmed), the speedup, the overhead per voyage (wall time per voyage x workers minus the mean
planning time alone), peak RSS per worker, whether the 2-worker plans equal the 1-worker
ones (and the one-by-one ones) bit for bit in fuel, and the measured constants a 1,000-voyage
extrapolation needs.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
import time
from datetime import UTC, datetime, timedelta

from shiproute_core.bench_report import print_figures

# (from, to, RTA days): North Pacific passages inside the bundled scenarios' grid
PASSAGES = (
    ("Busan", "Long Beach", 13.0), ("Yokohama", "Vancouver", 10.0),
    ("Kaohsiung", "Oakland", 16.0), ("Shanghai", "Busan", 2.0),
    ("Tokyo", "Honolulu", 9.0), ("Vancouver", "Honolulu", 7.0),
    ("Hong Kong", "Kaohsiung", 2.0), ("Busan", "Yokohama", 3.0),
)
DEPART0 = datetime(2026, 3, 2, 0, tzinfo=UTC)


def bench_voyages(n: int, budget: str) -> list:
    """`n` voyages: the passages at departures 18 h apart (different weather each)."""
    from ...fleet.voyages import VoyageSpec
    from ...plan_request import build_request

    out = []
    for k in range(n):
        a, b, days = PASSAGES[k % len(PASSAGES)]
        dep = DEPART0 + timedelta(hours=18 * (k // len(PASSAGES)))
        req = build_request(origin=a, destination=b, depart=dep.isoformat(), rta=f"{days}d",
                            budget=budget, seed=k)
        out.append(VoyageSpec(f"v{k:02d}", f"vessel{k % 10}", k + 2, req, None, f"v{k:02d}"))
    return out


def run_batch(voyages: list, workers: int, forecast: str, out_dir: str) -> dict:
    """One batch on a fresh LocalCluster: records, wall time, set-up time, peak RSS."""
    from ...fleet.runner import FleetOptions, run_fleet

    opts = FleetOptions(out_dir=out_dir, forecasts=(forecast,), workers=workers)
    run = run_fleet(voyages, opts, force=True, show_progress=False)
    peak = max(run.worker_peak_rss_mb.values()) if run.worker_peak_rss_mb else float("nan")
    return {"run": run, "peak_rss_mb": peak}


def alone(voyages: list, forecast: str) -> tuple[list[float], list[float], list[float]]:
    """Plan each voyage in this process (one thread, warmed): (wall s, CPU s, fuel t)."""
    from ...fleet.forecasts import cached_forecast
    from ...fleet.keys import forecast_key
    from ...fleet.plugin import warm_planner
    from ...plan_request import run_request
    from ...threads import set_planner_threads

    set_planner_threads(1)
    fc = cached_forecast(forecast, forecast_key(forecast))
    warm_planner(fc.sampler, fc.cycle_id)
    secs, cpu, fuel = [], [], []
    for v in voyages:
        t0, c0 = time.perf_counter(), time.process_time()
        plan = run_request(v.request, fc.sampler, cycle_id=fc.cycle_id)
        secs.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
        fuel.append(plan.total_fuel_t)
    return secs, cpu, fuel


def makespan_s(durations: list[float], workers: int) -> float:
    """Batch time when each task goes to the first idle worker in submission order (what the
    Dask scheduler does with equal-priority independent tasks)."""
    import heapq

    free = [0.0] * workers
    for d in durations:
        heapq.heapreplace(free, free[0] + d)
    return max(free)


def extrapolate(per_voyage_s: list[float], setup_s: float, n: int = 1000,
                workers: tuple[int, ...] = (2, 8, 32, 128)) -> dict:
    """Simulated cycle time of `n` voyages drawn (seeded) from the measured per-voyage
    times (planning + overhead on a worker) on clusters of `workers` single-thread workers,
    plus the measured worker set-up (in parallel on every worker, once per cycle)."""
    import numpy as np

    rng = np.random.default_rng(0)
    sample = rng.choice(np.asarray(per_voyage_s), size=n).tolist()
    return {f"{w}w": round(setup_s + makespan_s(sample, w), 1) for w in workers}


def run(n: int, budget: str, forecast: str) -> dict:
    """The benchmark's JSON result."""
    voyages = bench_voyages(n, budget)
    with tempfile.TemporaryDirectory() as tmp:
        one = run_batch(voyages, 1, forecast, os.path.join(tmp, "w1"))
        two = run_batch(voyages, 2, forecast, os.path.join(tmp, "w2"))
    secs, cpu_alone, fuel_alone = alone(voyages, forecast)

    def fuels(batch: dict) -> dict:
        return {r["voyage_id"]: r.get("fuel_t") for r in batch["run"].records}

    f1, f2 = fuels(one), fuels(two)
    ok = [r for r in two["run"].records if r["status"] == "planned"]
    w1, w2 = one["run"].wall_s, two["run"].wall_s
    mean_alone = statistics.fmean(secs)
    setup = [v.get("setup_s", float("nan")) for v in two["run"].worker_setup.values()]
    return {
        "voyages": n, "budget": budget, "forecast": forecast,
        "planned": len(ok), "failed": n - len(ok),
        "wall_s_1w": round(w1, 3), "wall_s_2w": round(w2, 3), "speedup": round(w1 / w2, 3),
        "overhead_per_voyage_s": round(w1 / n - mean_alone, 4),
        "overhead_per_voyage_s_2w": round(2 * w2 / n - mean_alone, 4),
        "plan_alone_mean_s": round(mean_alone, 4), "plan_alone_total_s": round(sum(secs), 3),
        "peak_rss_mb_per_worker": round(max(one["peak_rss_mb"], two["peak_rss_mb"]), 1),
        "identical_plans": f1 == f2,
        "identical_to_one_by_one": [f2[v.voyage_id] for v in voyages] == fuel_alone,
        "cluster_start_and_setup_s_1w": round(one["run"].start_s, 2),
        "cluster_start_and_setup_s_2w": round(two["run"].start_s, 2),
        "worker_setup_s": [round(s, 2) for s in setup],
        # load-robust parts of the overhead: CPU a voyage costs on a worker beyond planning
        # it alone (files, forecast look-up, task (de)serialisation), and the time the lone
        # worker waited between tasks (scheduler round trip)
        "overhead_cpu_per_voyage_s": round(
            sum(r.get("cpu_s", 0.0) for r in one["run"].records) / n - statistics.fmean(
                cpu_alone), 4),
        "idle_between_tasks_per_voyage_s_1w": round(
            (w1 - sum(r.get("wall_s", 0.0) for r in one["run"].records)) / n, 4),
        "plan_alone_cpu_mean_s": round(statistics.fmean(cpu_alone), 4),
        "task_cpu_s_1w": round(sum(r.get("cpu_s", 0.0) for r in one["run"].records), 2),
        "task_cpu_s_2w": round(sum(r.get("cpu_s", 0.0) for r in two["run"].records), 2),
        "cpus": os.cpu_count(), "load_avg_1m": round(os.getloadavg()[0], 2),
        "extrapolated_1000_voyages_s": extrapolate(
            [r["wall_s"] for r in one["run"].records if "wall_s" in r],
            max(setup) if setup else 0.0),
    }


def main(argv: list[str]) -> int:
    """`shiproute bench fleet [--json] [--voyages N] [--budget 2000ev] [--forecast NAME]`."""
    ap = argparse.ArgumentParser(prog="shiproute bench fleet", description=__doc__)
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--voyages", type=int, default=40)
    ap.add_argument("--budget", default="2000ev", help="evaluation budget per voyage")
    ap.add_argument("--forecast", default="storm_march")
    args = ap.parse_args(argv)
    res = run(args.voyages, args.budget, args.forecast)
    print_figures(res, args.json)
    return 0 if res["identical_plans"] and res["failed"] == 0 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
