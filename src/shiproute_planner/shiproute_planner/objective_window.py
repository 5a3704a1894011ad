"""How much time the route encoding of a leg spans for an objective that wants to arrive
early. The encoding has one stage per `stage_s` of the window it is given, and the GA can
only move the arrival within about a stage of that window's end; so an objective that values
time searches in the window it needs, while the RTA stays the constraint:

- eta: the great circle between the leg's ends at the ship's top calm-water speed, x 1.1;
- cost: the same distance at the calm-water speed that minimises the cost per metre,
  (fuel price x fuel rate + charter rate) / speed, x 1.1, and never below the eta window;
- fuel, distance, co2: the whole window up to the RTA.

Whatever the objective, the encoding spans no more than the leg takes at the engine's lowest
RPM in calm water over its sea lane (the great circle where there is none) x 1.1
(`slowest_window_s`): stages filling a window the ship cannot fill at its lowest RPM make
the GA's routes sail round to use it (Genoa -> Barcelona with 5 days, 20,000 evaluations:
387 NM and 8.47 t with the whole window, 373 NM and 8.16 t with this one; a window of 1.5
times the lane led Aberdeen -> Stornoway ~320 NM round a 235-NM lane).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .objectives import ObjectiveTerms

MARGIN = 1.1  # weather and the route's detour over the great circle
N_RPM = 60


def search_window_s(terms: ObjectiveTerms | None, model: Any, distance_m: float,
                    window_s: float) -> float:
    """Seconds the encoding should span (at most `window_s`, the time to the RTA)."""
    if terms is None or terms.name not in ("eta", "cost"):
        return window_s
    spec = getattr(model, "ship", None)
    if spec is None:
        return window_s
    rpm = np.linspace(spec.engine.rpm_min, spec.engine.rpm_max, N_RPM)
    perf = _calm(model, rpm)
    if perf is None:
        return window_s
    v = np.asarray(perf.stw_m_s, dtype=float)
    ok = np.isfinite(v) & (v > 0.1)
    if not np.any(ok):
        return window_s
    fastest_s = MARGIN * distance_m / float(v[ok].max())
    if terms.name == "eta":
        return min(fastest_s, window_s)
    per_m = (terms.per_t_fuel * np.asarray(perf.fuel_t_per_h)[ok] + terms.per_h) / v[ok]
    best_v = float(v[ok][int(np.argmin(per_m))])
    return min(max(MARGIN * distance_m / best_v, fastest_s), window_s)


def slowest_window_s(model: Any, distance_m: float) -> float:
    """Seconds `MARGIN` x `distance_m` [m] (a leg's sea lane) take at the ship's lowest RPM
    in calm water (inf when the model cannot tell)."""
    spec = getattr(model, "ship", None)
    perf = None if spec is None else _calm(model, np.array([float(spec.engine.rpm_min)]))
    if perf is None or distance_m <= 0.0:
        return float("inf")
    v = float(np.asarray(perf.stw_m_s, dtype=float)[0])
    if not (np.isfinite(v) and v > 0.1):
        return float("inf")
    return MARGIN * distance_m / v


def _calm(model: Any, rpm: np.ndarray) -> Any:
    """The model's performance at `rpm` on a heading in calm water (None when it cannot
    tell)."""
    from .ship import SeaState

    try:
        return model.evaluate(rpm, np.zeros(rpm.size), SeaState.calm(rpm.size))
    except (ValueError, ArithmeticError):
        return None
