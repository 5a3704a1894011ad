"""Run a fleet batch on Dask: a `LocalCluster` of worker processes on this machine by default,
or any running cluster by scheduler address. Voyages already planned from the same inputs are
skipped; the rest go to the workers as one task each (key = the voyage's input hash, retried
when it raises; a lost worker's tasks are re-run by the scheduler); results stream back into
the progress bar and the fleet records."""

from __future__ import annotations

import contextlib
import importlib.util
import os
import time
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from typing import Any, TextIO

from .errors import FleetError, SchedulerUnreachableError
from .keys import code_version, forecast_key, voyage_key
from .outputs import existing_result, remove_stale, safe_name
from .progress import FleetProgress
from .voyages import VoyageSpec
from .worker import VoyageTask, base_record

WORKER_ENV = {"SHIPROUTE_PLANNER_THREADS": "1", "NUMBA_NUM_THREADS": "1",
              "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
ALLOWED_FAILURES = 3  # worker deaths while running one voyage before it is given up


@dataclass(frozen=True)
class FleetOptions:
    """How to run a batch."""

    out_dir: str
    forecasts: tuple[str, ...] = ()  # specs; none = calm water
    scheduler: str | None = None  # tcp://host:port of a running cluster
    workers: int = 2  # LocalCluster worker processes
    seed_pool_dir: str | None = None
    png: bool = False
    retries: int = 2
    warm: bool = True
    connect_timeout_s: float = 10.0


@dataclass
class FleetRun:
    """Outcome of a batch: one record per voyage, timings and the cluster's description."""

    records: list[dict[str, Any]] = field(default_factory=list)
    dashboard: str = ""
    cluster: str = ""
    start_s: float = 0.0  # cluster start + worker set-up
    wall_s: float = 0.0  # first submission to last result
    worker_setup: dict[str, Any] = field(default_factory=dict)
    worker_peak_rss_mb: dict[str, float] = field(default_factory=dict)


def make_tasks(voyages: Sequence[VoyageSpec], opts: FleetOptions) -> tuple[list[VoyageTask],
                                                                             list[dict]]:
    """Voyages x forecasts -> tasks (a row naming a forecast gets that one only), plus the
    records of voyages naming a forecast that was not given."""
    code = code_version()
    specs: list[str | None] = list(opts.forecasts) or [None]
    keys = {s: forecast_key(s) for s in specs}
    extra = f"pool:{opts.seed_pool_dir}" if opts.seed_pool_dir else ""
    tasks, bad = [], []
    for v in voyages:
        chosen = specs
        if v.forecast is not None and v.forecast.lower() == "calm":
            chosen = [None]  # the row asks for calm water
            keys.setdefault(None, "calm")
        elif v.forecast is not None:
            chosen = [s for s in specs if s is not None and _names(s, v.forecast)]
            if not chosen:
                t = VoyageTask(v.voyage_id, "", v.request, v.forecast, "", opts.out_dir,
                               v.vessel, v.group, v.line)
                bad.append({**base_record(t), "status": "failed", "reason":
                            f"line {v.line}: forecast {v.forecast!r} is not among --forecast"})
                continue
        for s in chosen:
            vid = v.voyage_id if len(chosen) == 1 else f"{v.voyage_id}~{_label(s)}"
            key = voyage_key(v.request, keys[s], code, extra)
            tasks.append(VoyageTask(vid, key, v.request, s, keys[s], opts.out_dir, v.vessel,
                                    v.group, v.line, v.window_start_s, opts.seed_pool_dir,
                                    opts.png))
    return tasks, bad


def _label(spec: str | None) -> str:
    if spec is None:
        return "calm"
    return os.path.splitext(os.path.basename(spec.split("+")[0]))[0]


def _names(spec: str, wanted: str) -> bool:
    """Does a row's forecast value name this spec (the spec itself or its label)?"""
    return wanted in (spec, _label(spec))


def dashboard_available() -> bool:
    """The Dask dashboard needs bokeh."""
    return importlib.util.find_spec("bokeh") is not None


@contextlib.contextmanager
def fleet_client(opts: FleetOptions) -> Iterator[tuple[Any, str]]:
    """A connected `distributed.Client` and a description of its cluster."""
    try:
        import dask
        from distributed import Client, LocalCluster
    except ImportError as exc:
        raise FleetError(f"fleet planning needs dask.distributed ({exc}): "
                         "run ros2_ws/shiproute env to install the pinned requirements") from None

    # the worker's statistical profiler samples the planning thread every 10 ms: its CPU is
    # taken from the voyages (the nanny hands this configuration to the worker processes)
    with dask.config.set({"distributed.scheduler.allowed-failures": ALLOWED_FAILURES,
                          "distributed.worker.daemon": False,
                          "distributed.worker.profile.enabled": False}):
        if opts.scheduler:
            try:
                client = Client(opts.scheduler, timeout=f"{opts.connect_timeout_s}s")
            except (OSError, TimeoutError, ValueError) as exc:
                raise SchedulerUnreachableError(
                    f"no Dask scheduler answers at {opts.scheduler} within "
                    f"{opts.connect_timeout_s:g} s ({type(exc).__name__}: {exc}); start one "
                    "with `dask scheduler` or omit --scheduler for a local cluster") from None
            with client:
                yield client, f"scheduler {opts.scheduler}"
            return
        cluster = LocalCluster(
            n_workers=opts.workers, threads_per_worker=1, processes=True,
            dashboard_address=":0" if dashboard_available() else None, env=WORKER_ENV,
            silence_logs=40)
        with cluster, Client(cluster) as client:
            yield client, f"LocalCluster of {opts.workers} worker process(es), 1 thread each"


def run_fleet(voyages: Sequence[VoyageSpec], opts: FleetOptions, *, force: bool = False,
              stream: TextIO | None = None, show_progress: bool = True) -> FleetRun:
    """Plan every voyage (x forecast) not already planned from the same inputs."""
    from distributed import wait

    tasks, records = make_tasks(voyages, opts)
    run = FleetRun(records=list(records))
    todo = []
    for t in tasks:
        done = None if force else existing_result(t.out_dir, t.voyage_id, t.key)
        if done is not None:
            run.records.append({**done, "status": done.get("status", "planned"),
                                "already_planned": True})
        else:
            todo.append(t)
    specs_order: dict[str | None, int] = {s: k for k, s in enumerate(opts.forecasts)}
    progress = FleetProgress(len(tasks), cached=len(tasks) - len(todo), stream=stream)
    t0 = time.perf_counter()
    if todo:
        from .plugin import FleetWorkerSetup

        with fleet_client(opts) as (client, desc):
            run.cluster = desc
            run.dashboard = (client.dashboard_link if dashboard_available()
                             else "dashboard unavailable (bokeh is not installed)")
            if show_progress:
                print(f"fleet: {len(todo)} voyage(s) to plan on {desc}; dashboard: "
                      f"{run.dashboard}", file=progress.stream, flush=True)
            used = sorted({(t.forecast, t.forecast_key) for t in todo}, key=str)
            client.register_plugin(FleetWorkerSetup(used, threads=1, warm=opts.warm))
            run.worker_setup = client.run(lambda dask_worker: getattr(
                dask_worker, "shiproute_setup", {}))
            run.start_s = time.perf_counter() - t0
            t1 = time.perf_counter()
            progress.restart_clock()
            from .worker import plan_task

            # forecast by forecast: a worker holds a few forecasts, not every one at once
            todo.sort(key=lambda t: specs_order.get(t.forecast, 0))
            futures = {client.submit(plan_task, t, key=f"voyage-{safe_name(t.voyage_id)}-{t.key}",
                                     pure=False, retries=opts.retries): t for t in todo}
            pending = set(futures)
            while pending:
                try:
                    finished, _ = wait(list(pending), timeout=0.5, return_when="FIRST_COMPLETED")
                except TimeoutError:
                    finished = set()
                for fut in finished:
                    pending.discard(fut)
                    rec = _result(fut, futures[fut])
                    run.records.append(rec)
                    if rec["status"] == "failed":
                        progress.failed += 1
                    else:
                        progress.done += 1
                progress.running = min(len(pending), _slots(client))
                if show_progress:
                    progress.show()
            run.wall_s = time.perf_counter() - t1
            with contextlib.suppress(Exception):  # a statistic: never fail the batch for it
                run.worker_peak_rss_mb = client.run(peak_rss_mb)
    if show_progress:
        progress.close()
    for t in tasks:
        remove_stale(t.out_dir, t.voyage_id, t.key)
    order = {t.voyage_id: k for k, t in enumerate(tasks)}
    run.records.sort(key=lambda r: (order.get(r["voyage_id"], -1), r.get("line", 0)))
    return run


def peak_rss_mb(dask_worker: Any = None) -> float:
    """Peak resident set of the calling process in MB (Linux ru_maxrss is in kB)."""
    import resource

    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def _result(fut: Any, task: VoyageTask) -> dict[str, Any]:
    """A finished future's record; a task Dask gave up on (its workers kept dying, or it
    raised through every retry) becomes a failed record with the reason."""
    try:
        return fut.result()
    except Exception as exc:
        return {**base_record(task), "status": "failed",
                "reason": f"{type(exc).__name__}: {exc}"}


_SLOTS: dict[int, tuple[float, int]] = {}


def _slots(client: Any) -> int:
    """Worker threads of the cluster (looked up at most once a second)."""
    now = time.perf_counter()
    hit = _SLOTS.get(id(client))
    if hit is None or now - hit[0] > 1.0:
        try:
            n = sum(client.nthreads().values())
        except Exception:
            n = hit[1] if hit else 1
        hit = (now, n)
        _SLOTS[id(client)] = hit
    return hit[1]
