"""A re-plan's route arrives on time (`replan_retime`): the previous plan's remainder from a
ship ahead of its schedule (plan 1's position 48 h out, reached 5 h early) arrives hours
before the target (RTA - 0.5 h) at plan 1's RPMs, as the test's own leg-by-leg march shows.
Carried over, it is re-sailed at one RPM factor to within 1 h of the target, burns less fuel
than the march (slower is cheaper: power ~ speed cubed, time ~ 1 / speed) and breaks no
constraint. With the ship's Hs limit set between the highest sea the early remainder meets
and the highest the remainder slowed from the start meets (both marched by the test), only
the legs after the broken ones are slowed."""

from __future__ import annotations

from datetime import timedelta

import numpy as np
import pytest
from shiproute_core.geodesy import unwrap_near
from shiproute_planner.plan_position import position_after
from shiproute_planner.plan_prepare import prepare_voyage
from shiproute_planner.plan_setup import make_environment, route_limits
from shiproute_planner.planning import plan
from shiproute_planner.replan_keep import carried_legs, precheck
from shiproute_planner.request import PlanOptions, VoyageRequest, voyage_times
from shiproute_planner.route.problem import RouteProblem
from shiproute_planner.route.sail import sail_tracks
from shiproute_planner.rpm_factor import retimed_rpm

SHIP = "container_4600teu"
HOURS_ALONG = 48.0
EARLY_H = 5.0
TARGET_BEFORE_RTA_S = 1800.0  # the brief's target: half an hour before the RTA


def _voyage() -> VoyageRequest:
    depart_s, rta_s = voyage_times("2026-03-03T18:00Z", timedelta(days=13))
    return VoyageRequest("Busan", "Long Beach", depart_s, rta_s, SHIP)


@pytest.fixture(scope="module")
def previous(land_mask, storm_sampler):
    """Plan 1 on the March storm (reproducible: route evaluations), about on time."""
    out = plan(_voyage(), PlanOptions(land=land_mask, budget_s=600.0, max_evaluations=800,
                                      seed=3), storm_sampler)
    assert out.feasible
    assert abs(out.eta_s - out.rta_s) <= 3600.0
    return out


def _ahead(previous) -> tuple[float, float, float]:
    lat, lon, t = position_after(previous, HOURS_ALONG)
    return lat, lon, t - EARLY_H * 3600.0


def _remainder_rpm(previous, position) -> np.ndarray:
    _, _, t = previous.track()
    first = int(np.flatnonzero(t > position[2])[0])
    return previous.leg_rpm()[first - 1:]


def _marched(previous, position, rpm, sampler):
    """The previous plan's nodes ahead of the ship sailed at `rpm` per leg, leg by leg."""
    lon, lat, t = previous.track()
    first = int(np.flatnonzero(t > position[2])[0])
    r_lon = np.concatenate([[position[1]], unwrap_near(lon[first:], position[1])])
    r_lat = np.concatenate([[position[0]], lat[first:]])
    env, spec = make_environment(SHIP, sampler)
    problem = RouteProblem(r_lon[0], r_lat[0], r_lon[-1], r_lat[-1], position[2],
                           position[2] + 30 * 86400.0, route_limits(spec))
    return sail_tracks(problem, env, None, r_lon[None, :], r_lat[None, :], rpm[None, :])


def _carried(previous, position, sampler, land_mask, limits=None):
    options = PlanOptions(land=land_mask, method="great_circle", previous_plan=previous,
                          position=position, limits=limits)
    prep = prepare_voyage(_voyage(), options, sampler)
    legs = carried_legs(prep, options)
    assert not isinstance(legs, str), legs
    rpm = np.concatenate([p.legs["rpm"][0] for ev, (pre, post) in
                          zip(legs.results, legs.approaches, strict=True)
                          for p in (pre, ev, post) if p is not None])
    return legs, prep, rpm


def test_an_early_remainder_is_slowed_to_its_target_at_one_factor(previous, land_mask,
                                                                  storm_sampler):
    pos = _ahead(previous)
    target_s = previous.rta_s - TARGET_BEFORE_RTA_S
    plan_rpm = _remainder_rpm(previous, pos)
    early = _marched(previous, pos, plan_rpm, storm_sampler)
    assert early.violation[0] <= 0.0  # feasible as it is ...
    assert early.eta_s[0] < target_s - 4 * 3600.0  # ... but hours early
    legs, prep, rpm = _carried(previous, pos, storm_sampler, land_mask)
    assert legs.retimed and legs.said.startswith("re-timed: the previous plan's remainder")
    ok, _, fuel = precheck(legs, prep)
    assert ok
    assert abs(legs.arrivals[-1] - target_s) <= 3600.0
    assert fuel < float(early.fuel_t[0])
    factor = rpm / plan_rpm
    assert np.ptp(factor) <= 1e-9 and factor[0] < 1.0  # one factor, slower
    # the kept legs, marched independently at their RPMs, agree
    check = _marched(previous, pos, rpm, storm_sampler)
    assert check.violation[0] <= 0.0
    assert float(check.eta_s[0]) == pytest.approx(legs.arrivals[-1], abs=120.0)
    assert float(check.fuel_t[0]) == pytest.approx(fuel, rel=2e-3)


def test_slowing_into_the_storm_re_times_only_the_later_legs(previous, land_mask,
                                                             storm_sampler):
    pos = _ahead(previous)
    plan_rpm = _remainder_rpm(previous, pos)
    early = _marched(previous, pos, plan_rpm, storm_sampler)
    window_s = previous.rta_s - TARGET_BEFORE_RTA_S - pos[2]
    slowed = _marched(previous, pos, plan_rpm * float(early.eta_s[0] - pos[2]) / window_s,
                      storm_sampler)
    hs_early = float(np.nanmax(early.legs["hs_m"]))
    hs_slowed = float(np.nanmax(slowed.legs["hs_m"]))
    assert hs_slowed > hs_early + 0.1  # slowed from the start, the ship meets higher seas
    limit_m = 0.5 * (hs_early + hs_slowed)
    _, spec = make_environment(SHIP, None)
    lim = route_limits(spec)
    limits = {"rpm_min": lim.rpm_min, "rpm_max": lim.rpm_max, "max_hs_m": limit_m}
    legs, prep, rpm = _carried(previous, pos, storm_sampler, land_mask, limits)
    assert legs.retimed and " from leg " in legs.said, legs.said
    ok, _, fuel = precheck(legs, prep)
    assert ok
    assert abs(legs.arrivals[-1] - (previous.rta_s - TARGET_BEFORE_RTA_S)) <= 3600.0
    assert fuel < float(early.fuel_t[0])
    factor = rpm / plan_rpm
    kept = np.isclose(factor, 1.0, rtol=0.0, atol=1e-12)
    cut = int(np.argmin(kept))  # the first slowed leg
    assert cut > 0 and kept[:cut].all() and not kept[cut:].any()
    assert np.ptp(factor[cut:]) <= 1e-9 and factor[cut] < 1.0
    # the first legs at plan 1's times meet what the early march met: below the limit
    check = _marched(previous, pos, rpm, storm_sampler)
    assert float(np.nanmax(check.legs["hs_m"])) <= limit_m


def test_the_rpm_factor_fills_the_window_and_keeps_the_legs_before_the_cut():
    rpm = np.array([60.0, 70.0, 80.0, 90.0])
    dur = np.array([10.0, 10.0, 10.0, 10.0])
    # 40 s of legs in a 50-s window: all legs slowed by 40 / 50 (times scale as 1 / RPM)
    np.testing.assert_allclose(retimed_rpm(rpm, dur, 0, 50.0), rpm * 0.8)
    # the first two legs 20 s faster by 1.25 take 16 s: the last two get 34 s for their 20
    out = retimed_rpm(rpm, dur, 2, 50.0, 1.25)
    np.testing.assert_allclose(out, [75.0, 87.5, 80.0 * 20 / 34, 90.0 * 20 / 34])
    assert retimed_rpm(rpm, dur, 2, 20.0) is None  # nothing left for the later legs


DEMO_SHIP = (41.04, 139.14)  # the demo's replayed ship when cycle 2 arrives: past the
DEMO_SHIP_H = 35.0  # Tsugaru approach (it sails the constant-RPM baseline, not plan 1)


@pytest.fixture(scope="module")
def demo_plan1(land_mask):
    """The demo's plan 1 on cycle 1 from Busan (reproducible: route evaluations), on the
    half-precision forecast the planner node keeps."""
    from shiproute_weather.sampling.sampler import ForecastSampler
    from shiproute_weather.scenarios.catalogue import scenario_dataset

    sampler = ForecastSampler(scenario_dataset("storm_march"), dtype=np.float16)
    out = plan(_voyage(), PlanOptions(land=land_mask, budget_s=600.0, max_evaluations=4_000,
                                      seed=0), sampler)
    assert out.feasible
    return out


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_demo_re_plan_on_cycle_2_is_feasible_and_on_time(demo_plan1, land_mask, seed):
    from shiproute_weather.sampling.sampler import ForecastSampler
    from shiproute_weather.scenarios.catalogue import scenario_dataset

    cycle2 = ForecastSampler(scenario_dataset("storm_march_cycle2"), dtype=np.float16)
    voyage = _voyage()
    position = (*DEMO_SHIP, voyage.depart_s + DEMO_SHIP_H * 3600.0)
    out = plan(voyage, PlanOptions(land=land_mask, budget_s=600.0, max_evaluations=2_500,
                                   seed=seed, previous_plan=demo_plan1, position=position),
               cycle2)
    assert out.feasible, out.infeasible_reasons
    target_s = voyage.rta_s - TARGET_BEFORE_RTA_S
    assert abs(out.eta_s - target_s) <= 3600.0, [w for w in out.warnings if "re-timed" in w]
