"""How many threads one planning process uses for its own population chunks (evaluator and
ship-model pools): up to 4 cores by default, `SHIPROUTE_PLANNER_THREADS` or
`set_planner_threads` to fix it (a fleet worker plans on one thread so workers do not
compete for the same cores)."""

from __future__ import annotations

import os

_ENV = "SHIPROUTE_PLANNER_THREADS"
_override: int | None = None
_DEFAULT = max(1, min(4, os.cpu_count() or 1))  # read once: a sysfs read per call adds up


def planner_threads() -> int:
    """Threads a population evaluation may split over (>= 1)."""
    if _override is not None:
        return _override
    text = os.environ.get(_ENV, "").strip()
    if text.isdigit() and int(text) >= 1:
        return int(text)
    return _DEFAULT


def set_planner_threads(n: int) -> None:
    """Fix the planner's threads for this process (numba's too, for the compiled kernels)."""
    global _override
    if n < 1:
        raise ValueError(f"planner threads must be >= 1, got {n}")
    _override = int(n)
    import numba

    most = int(numba.config.NUMBA_NUM_THREADS)  # type: ignore[attr-defined]  # set at import
    numba.set_num_threads(min(int(n), most))
