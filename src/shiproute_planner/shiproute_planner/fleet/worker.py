"""What a fleet worker does for one voyage: plan it with the shared request runner on the
forecast this process holds, write RTZ/GeoJSON/JSON(/PNG) with the planner's io writers and
publish them atomically; any failure becomes a record with its reason (the batch goes on)."""

from __future__ import annotations

import math
import os
import socket
import time
import traceback
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from ..errors import PlannerError
from ..plan_request import PlanRequest, run_request
from .forecasts import cached_forecast
from .outputs import existing_result, publish


@dataclass(frozen=True)
class VoyageTask:
    """One voyage on one forecast, as sent to a worker (small and picklable)."""

    voyage_id: str
    key: str  # voyage_key: request + ship file + forecast + code version
    request: PlanRequest
    forecast: str | None  # forecast spec (None = calm water)
    forecast_key: str
    out_dir: str
    vessel: str = ""
    group: str = ""
    line: int = 0
    window_start_s: float | None = None
    seed_pool_dir: str | None = None
    png: bool = False


def _iso(t: float) -> str | None:
    if not math.isfinite(t):
        return None
    return datetime.fromtimestamp(t, UTC).strftime("%Y-%m-%dT%H:%M:%SZ")


def base_record(task: VoyageTask) -> dict[str, Any]:
    """Fields of a voyage's fleet record known before planning."""
    r = task.request
    return {
        "voyage_id": task.voyage_id, "group": task.group, "vessel": task.vessel,
        "line": task.line, "ship": r.ship, "model": r.model, "method": r.method,
        "objective": r.objective, "from": r.origin, "to": r.destination, "via": ";".join(r.via),
        "departure": _iso(r.depart_s), "rta": _iso(r.rta_s),
        "window_start": _iso(task.window_start_s) if task.window_start_s is not None else None,
        "budget": r.budget.label(), "seed": r.seed, "forecast": task.forecast or "calm",
        "forecast_key": task.forecast_key, "key": task.key,
    }


def plan_record(task: VoyageTask, plan: Any) -> dict[str, Any]:
    """A planned voyage's record: fuel against the constant-RPM baseline, ETA margin, flags and
    the plan's own warnings (forecast coverage, depth, route check: the planner states them)."""
    warnings = list(plan.warnings)
    if task.window_start_s is not None and plan.eta_s < task.window_start_s:
        warnings.append(f"arrives {(task.window_start_s - plan.eta_s) / 3600:.1f} h before "
                        "the arrival window opens")
    return {
        **base_record(task), "status": "planned", "reason": "",
        "feasible": bool(plan.feasible), "flags": ";".join(plan.infeasible_reasons),
        "warnings": ";".join(warnings), "fuel_t": plan.total_fuel_t,
        "baseline_fuel_t": plan.baseline_fuel_t, "baseline_feasible": plan.baseline_feasible,
        "fuel_saved_t": plan.fuel_saving_t, "fuel_saved_pct": plan.fuel_saving_pct,
        "eta": _iso(plan.eta_s), "eta_margin_h": (plan.rta_s - plan.eta_s) / 3600.0,
        "distance_nm": plan.total_distance_nm, "evaluations": plan.evaluations,
        "generations": plan.generations, "plan_s": plan.compute_time_s,
        "seed_source": plan.seed_source, "cycle_id": plan.cycle_id,
    }


def plan_task(task: VoyageTask) -> dict[str, Any]:
    """Plan one voyage and publish its outputs; returns its record (never raises for a
    voyage's own failure: status 'failed' and the reason)."""
    t0, cpu0 = time.perf_counter(), time.process_time()
    where = f"{socket.gethostname()}:{os.getpid()}"
    done = existing_result(task.out_dir, task.voyage_id, task.key)
    if done is not None:  # a re-run of a task whose first run had already published
        return {**done, "worker": where, "duplicate_run": True}
    try:
        fc = cached_forecast(task.forecast, task.forecast_key)
        plan = run_request(task.request, fc.sampler if fc else None,
                           cycle_id=fc.cycle_id if fc else "",
                           seed_pool_dir=task.seed_pool_dir)

        def write(tmp: Path) -> dict[str, Any]:
            from ..io.files import write_plan_files

            write_plan_files(plan, tmp, stem="plan", forecast=fc.dataset if fc else None,
                             png=task.png)
            return plan_record(task, plan)

        record, _ = publish(task.out_dir, task.voyage_id, task.key, write)
    except PlannerError as exc:
        record = {**base_record(task), "status": "failed", "reason": str(exc)}
    except Exception as exc:  # a bug must not stop the fleet: report it with where it was
        tb = traceback.extract_tb(exc.__traceback__)[-1]
        record = {**base_record(task), "status": "failed",
                  "reason": f"internal error {type(exc).__name__}: {exc} "
                            f"({Path(tb.filename).name}:{tb.lineno})"}
    return {**record, "worker": where, "wall_s": time.perf_counter() - t0,
            "cpu_s": time.process_time() - cpu0}
