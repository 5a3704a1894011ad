"""Projected descent of the GA's best (`ga.polish`) on problems with a known optimum."""

from __future__ import annotations

import time

import numpy as np
from shiproute_planner.ga.loop import GAConfig, SeedGA
from shiproute_planner.ga.polish import PolishConfig, polish

N = 6  # stages: 6 heading genes, 7 RPM genes
RTA_S = 1000.0
LO = np.r_[np.full(N, -30.0), np.full(N + 1, 20.0)]
HI = np.r_[np.full(N, 30.0), np.full(N + 1, 100.0)]


def cube_law(x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Fuel sum(rpm^3) per unit time over equal stages, ETA falling with the summed RPMs
    (ETA = 3000 - 5 sum(rpm)), late = violation. At a fixed RPM sum, sum(rpm^3) is least
    with equal RPMs (power mean inequality): the optimum on time is rpm = 2000 / 5 / 7."""
    rpm = x[:, N:]
    eta = 3000.0 - 5.0 * rpm.sum(axis=1)
    return np.maximum(eta - RTA_S, 0.0) / 3600.0, (rpm ** 3).sum(axis=1) * 1e-5, eta


def test_descends_to_the_even_profile_on_time() -> None:
    start = np.r_[np.zeros(N), np.linspace(45.0, 75.0, N + 1)]  # sum 420: 100 s early
    cfg = PolishConfig(with_headings=False, max_rounds=200, eta_margin_s=0.0)
    r = polish(start, cube_law, LO, HI, N, RTA_S, time.perf_counter() + 10.0, config=cfg)
    v, f, eta = cube_law(r.x[None, :])
    best_rpm = 2000.0 / 5.0 / (N + 1)
    optimum = (N + 1) * best_rpm ** 3 * 1e-5
    assert v[0] == 0.0 and eta[0] <= RTA_S
    assert f[0] <= optimum * 1.003  # within 0.3 % of the analytic optimum
    assert f[0] < cube_law(start[None, :])[1][0] * 0.9  # the start wasted > 10 %
    np.testing.assert_allclose(r.x[N:], best_rpm, atol=1.5)


def test_never_worse_and_within_its_evaluation_budget() -> None:
    start = np.r_[np.zeros(N), np.full(N + 1, 2000.0 / 5.0 / (N + 1))]  # already optimal
    r = polish(start, cube_law, LO, HI, N, RTA_S, time.perf_counter() + 10.0,
               max_evaluations=40, config=PolishConfig(eta_margin_s=0.0))
    assert r.evaluations <= 40
    assert r.violation == 0.0
    assert r.objective <= cube_law(start[None, :])[1][0] + 1e-12


def test_injected_genes_rank_in_without_a_generation() -> None:
    rng = np.random.default_rng(0)
    ga = SeedGA(LO, HI, N, GAConfig(pop_size=8, offspring=8), rng)
    x = ga.ask()
    v, f, _ = cube_law(x)
    ga.tell(x, v, f)
    gen, evals = ga.generation, ga.evaluations
    better = np.r_[np.zeros(N), np.full(N + 1, 2000.0 / 5.0 / (N + 1))][None, :]
    bv, bf, _ = cube_law(better)
    ga.inject(better, bv, bf, spent=25)
    assert ga.generation == gen and ga.evaluations == evals + 25
    assert len(ga.pop) == 8 and np.array_equal(ga.best[0], better[0])
