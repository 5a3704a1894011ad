"""Every span of a re-plan starts from the previous plan's route between its ends, its RPMs
scaled by the previous time over the span's window (speed ~ RPM): the ocean span after a
strait is seeded, not only the first span."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from shiproute_planner.plan_request import build_request, run_request
from shiproute_planner.plan_seeds import previous_span_seed
from shiproute_planner.plan_setup import route_limits
from shiproute_planner.route.problem import RouteProblem

LIMITS = route_limits(None, {"rpm_min": 30.0, "rpm_max": 104.0})


@pytest.fixture(scope="module")
def previous():
    # open Pacific, calm water: one optimised span of ~10 twelve-hour stages
    return run_request(build_request(origin="35,160", destination="38,190",
                                     depart="2026-03-10T00:00Z", rta="5d", budget="800ev"))


def _span(plan, i: int, j: int, stretch: float, start=None) -> RouteProblem:
    lon, lat, t = plan.track()
    lon0, lat0, t0 = start if start is not None else (lon[i], lat[i], t[i])
    return RouteProblem(float(lon0), float(lat0), float(lon[j]), float(lat[j]), float(t0),
                        float(t0 + stretch * (t[j] - t0)), LIMITS)


def test_a_later_span_gets_the_previous_route_between_its_ends(previous) -> None:
    lon, lat, t = previous.track()
    i, j = 3, len(t) - 3
    assert j - i >= 3
    seed = previous_span_seed(previous, _span(previous, i, j, 1.25), under_way=False)
    assert seed is not None and seed.source == "previous_plan"
    np.testing.assert_allclose(seed.lon_deg, lon[i:j + 1], atol=1e-9)
    np.testing.assert_allclose(seed.lat_deg, lat[i:j + 1], atol=1e-9)
    # 25 % more time over the same route: the RPMs of those legs x 1 / 1.25
    np.testing.assert_allclose(seed.rpm, previous.leg_rpm()[i:j] / 1.25, rtol=1e-9)
    same = previous_span_seed(previous, _span(previous, i, j, 1.0), under_way=False)
    np.testing.assert_allclose(same.rpm, previous.leg_rpm()[i:j], rtol=1e-9)


def test_under_way_the_seed_starts_at_the_ship(previous) -> None:
    lon, lat, t = previous.track()
    k = 4
    f = 0.5  # half way along leg k -> k + 1 (a straight line is near enough for the seed)
    ship = (lon[k] + f * (lon[k + 1] - lon[k]), lat[k] + f * (lat[k + 1] - lat[k]),
            t[k] + f * (t[k + 1] - t[k]))
    j = len(t) - 2
    seed = previous_span_seed(previous, _span(previous, k, j, 1.0, start=ship), under_way=True)
    assert seed is not None
    assert seed.lon_deg[0] == pytest.approx(ship[0]) and seed.lat_deg[0] == ship[1]
    np.testing.assert_allclose(seed.lon_deg[1:], lon[k + 1:j + 1], atol=1e-9)
    assert seed.rpm.size == seed.lon_deg.size - 1
    np.testing.assert_allclose(seed.rpm, previous.leg_rpm()[k:j], rtol=1e-9)


def test_a_replan_seeds_from_the_previous_plan_and_keeps_its_fuel(previous) -> None:
    # the same voyage again with the previous plan and no search beyond its seeds: the
    # plan cannot be worse than the previous route it was seeded with (same forecast)
    req = build_request(origin="35,160", destination="38,190", depart="2026-03-10T00:00Z",
                        rta="5d", budget="200ev")
    again = run_request(dataclasses.replace(req, seed=5), previous_plan=previous)
    assert again.feasible
    assert again.total_fuel_t <= previous.total_fuel_t * 1.002
