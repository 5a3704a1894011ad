"""Dask worker set-up for fleet planning: one planner thread per worker, the batch's forecasts
loaded and the compiled kernels, land mask and sea-lane graph warmed once per worker (a
restarted worker runs it again), before any voyage is planned there."""

from __future__ import annotations

import time
from typing import Any

from distributed.diagnostics.plugin import WorkerPlugin

from .forecasts import cached_forecast

WARM_VOYAGE = ("35.0,141.5", "36.5,146.0")  # open sea east of Japan, inside the scenarios


def warm_planner(forecast: Any = None, cycle_id: str = "") -> float:
    """Plan one short voyage at a tiny evaluation budget (loads the land mask, ports and
    sea-lane graph and compiles or loads every kernel); returns its seconds."""
    from ..plan_request import build_request, run_request

    t0 = time.perf_counter()
    req = build_request(origin=WARM_VOYAGE[0], destination=WARM_VOYAGE[1],
                        depart="2026-03-04T00:00Z", rta="30h", budget="60ev")
    run_request(req, forecast, cycle_id=cycle_id)
    return time.perf_counter() - t0


class FleetWorkerSetup(WorkerPlugin):
    """Worker plugin: threads, forecasts (spec, content key) and warm-up, once per worker."""

    name = "shiproute-fleet-setup"

    def __init__(self, forecasts: list[tuple[str | None, str]], threads: int = 1,
                 warm: bool = True) -> None:
        self.forecasts = list(forecasts)
        self.threads = threads
        self.warm = warm

    def setup(self, worker: Any) -> None:
        """Runs in the worker process when the plugin is registered or the worker starts."""
        from ..threads import set_planner_threads

        t0 = time.perf_counter()
        set_planner_threads(self.threads)
        first = None
        for spec, key in self.forecasts:
            fc = cached_forecast(spec, key)
            first = first or fc
        warm_s = warm_planner(first.sampler if first else None,
                              first.cycle_id if first else "") if self.warm else 0.0
        worker.shiproute_setup = {"setup_s": time.perf_counter() - t0, "warm_s": warm_s}
