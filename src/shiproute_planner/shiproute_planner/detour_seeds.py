"""Repairs of a stale re-plan's seed in gene space: the previous route bent round the stretch
where the new forecast breaks it (a storm that moved onto the track) and retimed (passing it
earlier or later), so a search too short for a cold plan's seeds still starts close to the
route the ship sails, at the cost of one evaluation of a small population."""

from __future__ import annotations

import numpy as np

from .route.evaluation import RouteEvaluation

# heading offsets of a detour [deg]: turned away before the broken stretch's middle and back
# after it, over as many stages as the stretch and a taper span
DETOUR_TURNS_DEG = (4.0, 8.0, 14.0)
DETOUR_TAPER_STAGES = 1  # stages of turn beyond the broken stretch on each side
RETIME_SCALES = (0.99, 1.0, 1.01, 1.02, 1.04)  # RPM factors of retimed copies ...
RETIME_SLOPES = (-0.12, -0.06, 0.0, 0.06, 0.12)  # ... and their ramps over the stages
RETIMED_ROWS = 4  # best seeds retimed


def broken_legs(ev: RouteEvaluation, row: int) -> np.ndarray:
    """Legs (stages) of route `row` that break a constraint (lateness alone breaks none)."""
    return np.flatnonzero(ev.leg_flags[row] != 0)


def detour_genes(x: np.ndarray, n_stages: int, bad: np.ndarray, lo: np.ndarray,
                 hi: np.ndarray) -> np.ndarray:
    """Copies of genes `x` (one row) that turn DETOUR_TURNS_DEG to one side where the broken
    legs `bad` start (a taper earlier), twice that back at their middle and onto the old
    course where they end (a taper later), to either side:
    the route bent round the stretch where the new forecast breaks it, in one evaluation."""
    bad = bad[bad < n_stages]
    if bad.size == 0:
        return np.empty((0, x.size))
    mid = (int(bad.min()) + int(bad.max()) + 1) // 2
    width = max(mid - int(bad.min()), int(bad.max()) + 1 - mid, 1) + DETOUR_TAPER_STAGES
    a, b = max(mid - width, 0), min(mid + width, n_stages)
    out = []
    for turn in DETOUR_TURNS_DEG:
        for side in (-1.0, 1.0):
            y = x.copy()  # genes 1..n-1 are heading changes (gene 0 the first heading)
            y[a] += side * turn
            y[mid] -= 2.0 * side * turn
            if b < n_stages:
                y[b] += side * turn
            out.append(y)
    return np.clip(np.array(out), lo, hi)


def retimed_genes(x: np.ndarray, n_stages: int, lo: np.ndarray, hi: np.ndarray
                  ) -> np.ndarray:
    """Copies of genes `x` (rows) with their RPMs scaled by RETIME_SCALES and ramped by
    RETIME_SLOPES (relative change first to last stage / 2): passing a storm earlier or
    later, or making up the minutes a seed's conversion to stages lost, costs one
    evaluation of a small population instead of generations."""
    ramp = np.linspace(-1.0, 1.0, n_stages + 1)
    out = []
    for scale in RETIME_SCALES:
        for slope in RETIME_SLOPES:
            y = x.copy()
            y[:, n_stages:] *= scale * (1.0 + slope * ramp)[None, :]
            out.append(y)
    return np.clip(np.concatenate(out), lo, hi)
