"""Consecutive parts of one sailed route (single-row evaluations, each starting where the one
before ends) joined into one evaluation, judged on the parts that decide: a kept plan's leg
that holds two optimised spans with a computed strait passage between them is one leg of the
plan, feasible only when both spans are."""

from __future__ import annotations

from collections.abc import Sequence
from itertools import pairwise

import numpy as np

from .evaluation import RouteEvaluation


def joined(parts: Sequence[tuple[RouteEvaluation, bool]]) -> RouteEvaluation:
    """One route from `parts` ((evaluation, decides) in sailing order, one row each): nodes
    joined at the shared ends, leg arrays side by side (every leg keeps its own flags),
    totals summed; the route's flags and violation are those of the deciding parts only.
    The objective is summed: every objective is additive over parts that each start at
    their own first node (fuel, distance, time under way, CO2, cost)."""
    if not parts:
        raise ValueError("joined: no parts to join")
    evs = [ev for ev, _ in parts]
    if len(evs) == 1 and parts[0][1]:
        return evs[0]
    for before, after in pairwise(evs):
        if abs(float(after.time_s[0, 0]) - float(before.eta_s[0])) > 1.0:
            raise ValueError("joined: a part does not start when the one before it ends")

    def nodes(name: str) -> np.ndarray:
        first = getattr(evs[0], name)[0]
        return np.concatenate([first, *(getattr(e, name)[0, 1:] for e in evs[1:])])[None, :]

    keys = [k for k in evs[0].legs if all(k in e.legs for e in evs[1:])]
    flags = np.zeros(1, dtype=evs[0].flags.dtype)
    violation = np.zeros(1)
    for ev, decides in parts:
        if decides:
            flags |= ev.flags[:1]
            violation = violation + ev.violation[:1]
    return RouteEvaluation(
        nodes("lon_deg"), nodes("lat_deg"), nodes("time_s"),
        {k: np.concatenate([e.legs[k] for e in evs], axis=1) for k in keys},
        np.concatenate([e.leg_flags for e in evs], axis=1),
        np.array([sum(float(e.fuel_t[0]) for e in evs)]),
        np.array([sum(float(e.distance_m[0]) for e in evs)]),
        evs[-1].eta_s[:1].copy(), flags, violation,
        np.array([sum(float(e.objective[0]) for e in evs)]))
