"""Deb's feasibility-first ordering: feasible by objective, then infeasible by violation."""

from __future__ import annotations

import numpy as np


def deb_order(violation: np.ndarray, objective: np.ndarray) -> np.ndarray:
    """Indices from best to worst under Deb's rules (stable for equal keys)."""
    v = np.asarray(violation, dtype=float)
    f = np.where(np.isfinite(objective), objective, np.inf)
    feasible = v <= 0.0
    # feasible first (key 0), ordered by objective; infeasible by violation
    primary = np.where(feasible, 0, 1)
    secondary = np.where(feasible, f, v)
    return np.lexsort((secondary, primary))


def is_better(v_a: float, f_a: float, v_b: float, f_b: float) -> bool:
    """True if (violation, objective) a beats b under Deb's rules."""
    if v_a <= 0.0 and v_b <= 0.0:
        return f_a < f_b
    if v_a <= 0.0 or v_b <= 0.0:
        return v_a <= 0.0
    return v_a < v_b
