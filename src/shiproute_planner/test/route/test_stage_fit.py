"""A span whose window is a whole number of derived stages keeps one stage of time for its
final connection (the Busan -> Tsugaru span of `bench planner` had none: its RTA fell where
the last stage ended, so only a route whose last node hit the port to the metre was on time,
and the seed GA spent its share of the budget without a feasible candidate)."""

from __future__ import annotations

import numpy as np
import pytest
from shiproute_planner.route.problem import RouteLimits, RouteProblem
from shiproute_planner.voyage.stage_length import MIN_STAGE_H, OCEAN_STAGE_H, default_stage_hours

LIMITS = RouteLimits(rpm_min=40.0, rpm_max=80.0)


def problem(window_s: float, stage_s: float) -> RouteProblem:
    return RouteProblem(129.0, 35.0, 140.0, 41.0, 0.0, window_s, LIMITS, stage_s=stage_s)


def test_bench_span_gets_its_final_connection() -> None:
    # the bench's first span: 36.2 h shared into 4 stages + the connection; the division
    # reads 5.000000000000001 stages in floating point
    window_s = 130168.70948410034
    stage_s = default_stage_hours(window_s, 4) * 3600.0
    assert window_s / stage_s > 5.0  # the floating-point hair the fit must not count
    p = problem(window_s, stage_s)
    assert p.n_stages == 4
    assert window_s - p.n_stages * stage_s == pytest.approx(stage_s, rel=1e-9)


@pytest.mark.parametrize("target", [4, 5, 8, 12])
def test_derived_stages_leave_one_stage_for_the_connection(target: int) -> None:
    # any window between the 6-minute floor and the 12-hour cap: `target` stages and one
    # stage for the connection
    rng = np.random.default_rng(target)
    for window_s in rng.uniform(MIN_STAGE_H, OCEAN_STAGE_H, 500) * 3600.0 * (target + 1):
        stage_s = default_stage_hours(float(window_s), target) * 3600.0
        p = problem(float(window_s), stage_s)
        assert p.n_stages == target
        assert window_s - p.n_stages * stage_s == pytest.approx(stage_s, rel=1e-9)


def test_window_past_whole_stages_keeps_the_remainder() -> None:
    # 12-hour stages over 10 days and 5 hours: 20 stages, the connection gets 17 h
    p = problem(10 * 86400.0 + 5 * 3600.0, 12 * 3600.0)
    assert p.n_stages == 20
