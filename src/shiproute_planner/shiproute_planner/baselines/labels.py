"""Label pruning for time-dependent dynamic programming: per node, a time-binned Pareto set.

3DDP (Shao-style) and the two-stage RPM schedule keep at each node the labels (arrival time,
fuel) that can still be optimal: within one arrival-time bin only the least fuel survives
(the "same arrival time, keep the minimum fuel" rule), and across bins only labels not
dominated by an earlier, cheaper one. Everything is array code over all nodes at once.
"""

from __future__ import annotations

import numpy as np


def prune_labels(
    group: np.ndarray,
    time_s: np.ndarray,
    fuel_t: np.ndarray,
    bin_s: float,
    pareto: bool = True,
    max_per_group: int | None = None,
) -> np.ndarray:
    """Indices of the labels to keep, sorted by (group, time).

    `group` is the node each label sits at (non-negative ints), `bin_s` the arrival-time bin
    width. With `pareto`, a label survives only if its fuel is strictly below every label of
    the same group that arrives earlier. `max_per_group` thins a group evenly in time.
    """
    n = group.size
    if n == 0:
        return np.zeros(0, dtype=np.int64)
    g = group.astype(np.int64)
    tbin = np.floor(time_s / bin_s).astype(np.int64)
    order = np.lexsort((fuel_t, tbin, g))
    gs, bs = g[order], tbin[order]
    first = np.ones(n, dtype=bool)
    first[1:] = (gs[1:] != gs[:-1]) | (bs[1:] != bs[:-1])
    keep = order[first]
    # re-sort survivors by (group, exact time) for the Pareto sweep
    keep = keep[np.lexsort((time_s[keep], g[keep]))]
    if pareto and keep.size > 1:
        gk = g[keep]
        f = fuel_t[keep]
        span = float(np.ptp(f)) + 1.0
        shifted = f - gk.astype(np.float64) * (span * 4.0)
        running = np.minimum.accumulate(shifted)
        new_group = np.ones(keep.size, dtype=bool)
        new_group[1:] = gk[1:] != gk[:-1]
        better = np.ones(keep.size, dtype=bool)
        better[1:] = shifted[1:] < running[:-1]
        keep = keep[new_group | better]
    if max_per_group is not None and keep.size:
        keep = _thin(g[keep], keep, max_per_group)
    return keep


def _thin(gk: np.ndarray, keep: np.ndarray, cap: int) -> np.ndarray:
    """Keep at most `cap` labels per group, evenly spaced in the (time-sorted) group order."""
    starts = np.flatnonzero(np.r_[True, gk[1:] != gk[:-1]])
    counts = np.diff(np.r_[starts, gk.size])
    if counts.max() <= cap:
        return keep
    rank = np.arange(gk.size) - np.repeat(starts, counts)
    size = np.repeat(counts, counts)
    step = np.maximum(size / cap, 1.0)
    # a label survives if it is the first of its slot when the group is cut into `cap` slots
    slot = np.floor(rank / step).astype(np.int64)
    first_in_slot = np.r_[True, (slot[1:] != slot[:-1]) | (gk[1:] != gk[:-1])]
    last = np.r_[gk[1:] != gk[:-1], True]  # always keep the cheapest (latest) label
    return keep[first_in_slot | last]
