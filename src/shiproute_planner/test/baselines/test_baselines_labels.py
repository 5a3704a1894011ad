"""Label pruning of the DP baselines against a brute-force Pareto filter."""

from __future__ import annotations

import numpy as np
from shiproute_planner.baselines.labels import prune_labels


def _brute(group, time_s, fuel_t, bin_s):
    keep = set()
    for g in np.unique(group):
        idx = np.flatnonzero(group == g)
        best_in_bin = {}
        for i in idx:
            b = int(np.floor(time_s[i] / bin_s))
            if b not in best_in_bin or fuel_t[i] < fuel_t[best_in_bin[b]]:
                best_in_bin[b] = i
        cand = sorted(best_in_bin.values(), key=lambda i: time_s[i])
        running = np.inf
        for i in cand:
            if fuel_t[i] < running:
                keep.add(int(i))
                running = fuel_t[i]
    return keep


def test_prune_matches_brute_force_pareto() -> None:
    rng = np.random.default_rng(3)
    group = rng.integers(0, 7, 600)
    time_s = rng.uniform(0, 50_000, 600)
    fuel_t = rng.uniform(10, 100, 600)
    got = prune_labels(group, time_s, fuel_t, bin_s=1000.0)
    assert set(got.tolist()) == _brute(group, time_s, fuel_t, 1000.0)
    # survivors are Pareto-optimal within their group: later arrival means strictly less fuel
    for g in range(7):
        sel = got[group[got] == g]
        order = np.argsort(time_s[sel])
        assert np.all(np.diff(fuel_t[sel][order]) < 0)


def test_cap_keeps_both_ends_of_each_front() -> None:
    time_s = np.arange(100.0)
    fuel_t = 200.0 - time_s
    group = np.zeros(100, dtype=np.int64)
    got = prune_labels(group, time_s, fuel_t, bin_s=0.5, max_per_group=10)
    assert got.size <= 11
    assert 0 in got and 99 in got
