"""The CLI's process warm-up: one calm-water set-up of the voyage before `--budget` starts.

A one-shot `shiproute plan` process loads its compiled kernels, land and depth maps, the
sea-lane graph and the coastal passages on its first plan; counted in the budget they left
the search well under a second of a 3-s budget (0 generations on an ocean crossing). The
planner node warms up the same way at start (`ros.startup.warm_planner`); here it is stated
in the plan's timing and on stderr.
"""

from __future__ import annotations

import dataclasses
import time
from typing import Any

from ..plan_request import PlanRequest, run_request


def warm_up(req: PlanRequest, keywords: dict[str, Any]) -> float:
    """Set `req`'s voyage up once in calm water with no search, no baseline and no seed
    pool; returns the seconds it took (raises what planning the voyage raises)."""
    t0 = time.perf_counter()
    calm = {k: v for k, v in keywords.items() if k not in ("risk", "cycle_id")}
    run_request(dataclasses.replace(req, objective="fuel"), None, **calm, budget_s=0.0,
                max_generations=0, with_baseline=False)
    return time.perf_counter() - t0


def warm_up_note(seconds: float, built: tuple[str, ...] = ()) -> str:
    """The stderr line that says what the warm-up did and that the budget excludes it
    (`built`: what it built for this machine, once, from `first_builds`)."""
    from ..geo.full_land import first_builds_clause

    once = first_builds_clause(built)
    return (f"warm-up: {seconds:.1f} s before the budget's clock (compiled kernels, land "
            f"and depth maps, sea lanes, coastal passages; once per process{once})")
