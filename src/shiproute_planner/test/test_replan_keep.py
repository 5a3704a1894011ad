"""A re-plan never silently gets worse (`replan_keep`): a starved search on a forecast where
the previous plan stays feasible publishes a feasible plan no worse than the previous plan's
remainder, checked against an independent evaluation of that remainder (the planner's leg by
leg march `sail_tracks` over the previous plan's own nodes, one piece, no cutting); and the
planner bench's warm re-plan (storm moved onto the route in cycle 2) ends feasible."""

from __future__ import annotations

from datetime import timedelta

import numpy as np
import pytest
from shiproute_core.geodesy import unwrap_near
from shiproute_planner.plan_position import position_after
from shiproute_planner.plan_setup import make_environment, route_limits
from shiproute_planner.planning import plan
from shiproute_planner.request import PlanOptions, VoyageRequest, voyage_times
from shiproute_planner.route.problem import RouteProblem
from shiproute_planner.route.sail import sail_tracks
from shiproute_planner.route.sail_fixed_point import sail_track

SHIP = "container_4600teu"


def _voyage() -> VoyageRequest:
    depart_s, rta_s = voyage_times("2026-03-03T18:00Z", timedelta(days=13))
    return VoyageRequest("Busan", "Long Beach", depart_s, rta_s, SHIP)


def _remainder_sailed(previous, position, sampler):
    """The previous plan's nodes after the ship's time, from its position, sailed at the
    plan's leg RPMs by the march (one piece): (evaluation, max Hs per leg limit)."""
    lon, lat, t = previous.track()
    first = int(np.flatnonzero(t > position[2])[0])
    r_lon = np.unwrap(np.concatenate([[position[1]], unwrap_near(lon[first:], position[1])]),
                      period=360.0)
    r_lat = np.concatenate([[position[0]], lat[first:]])
    rpm = previous.leg_rpm()[first - 1:]
    env, spec = make_environment(SHIP, sampler)
    lim = route_limits(spec)
    problem = RouteProblem(r_lon[0], r_lat[0], r_lon[-1], r_lat[-1], position[2],
                           position[2] + 30 * 86400.0, lim)
    return sail_tracks(problem, env, None, r_lon[None, :], r_lat[None, :], rpm[None, :]), lim


@pytest.fixture(scope="module")
def previous_plan(land_mask, storm_sampler):
    """A seed-GA plan on the March storm, reproducible (route evaluations, not wall time)."""
    p = plan(_voyage(), PlanOptions(land=land_mask, budget_s=600.0, max_evaluations=800,
                                    seed=3), storm_sampler)
    assert p.feasible
    return p


@pytest.mark.parametrize("hours", [6.0, 60.0])
def test_starved_replan_keeps_the_feasible_previous_plan(previous_plan, land_mask,
                                                         storm_sampler, hours):
    # a "search" that cannot end feasible (the constant-RPM great circle runs into the storm
    # and over land) on the forecast the previous plan was made on: the previous plan's
    # remainder is published, exactly as the independent march sails it
    voyage = _voyage()
    pos = position_after(previous_plan, hours)
    sailed, lim = _remainder_sailed(previous_plan, pos, storm_sampler)
    assert sailed.eta_s[0] <= voyage.rta_s + voyage.rta_tolerance_s  # still on time ...
    assert np.nanmax(sailed.legs["hs_m"]) <= lim.max_hs_m  # ... and below the Hs limit
    out = plan(voyage, PlanOptions(land=land_mask, method="great_circle",
                                   previous_plan=previous_plan, position=pos), storm_sampler)
    assert out.feasible
    assert out.extra["replan"]["kept_previous"] is True
    assert out.extra["replan"]["new_feasible"] is False
    assert any(w.startswith("kept previous plan: new search ended infeasible after 0 gens")
               for w in out.warnings)
    assert out.total_fuel_t == pytest.approx(float(sailed.fuel_t[0]), rel=1e-4)
    assert out.eta_s == pytest.approx(float(sailed.eta_s[0]), abs=30.0)
    assert out.departure_s == pos[2]


def test_starved_seed_ga_replan_is_no_worse_than_the_previous_remainder(
        previous_plan, land_mask, storm_sampler):
    voyage = _voyage()
    pos = position_after(previous_plan, 30.0)
    sailed, _ = _remainder_sailed(previous_plan, pos, storm_sampler)
    out = plan(voyage, PlanOptions(land=land_mask, budget_s=600.0, max_evaluations=1,
                                   max_generations=0, previous_plan=previous_plan,
                                   position=pos), storm_sampler)
    assert out.feasible
    assert out.total_fuel_t <= float(sailed.fuel_t[0]) * (1.0 + 1e-4)
    block = out.extra["replan"]
    assert block["previous_remaining_fuel_t"] == pytest.approx(float(sailed.fuel_t[0]),
                                                               rel=1e-4)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_warm_replan_on_the_moved_storm_is_feasible(previous_plan, land_mask, seed):
    # the planner bench's warm case: 6 h along, forecast cycle 2 puts the storm on the
    # previous route (its remainder breaks the Hs limit); 2,000 route evaluations are what
    # the ~0.25 s of search of a 0.5-s re-plan buys at the GA loop's ~8,000/s (idle core)
    from shiproute_weather.sampling.sampler import ForecastSampler
    from shiproute_weather.scenarios.catalogue import scenario_dataset

    cycle2 = ForecastSampler(scenario_dataset("storm_march_cycle2"), dtype=np.float16)
    pos = position_after(previous_plan, 6.0)
    out = plan(_voyage(), PlanOptions(land=land_mask, budget_s=600.0, max_evaluations=2000,
                                      seed=seed, previous_plan=previous_plan, position=pos,
                                      with_baseline=False), cycle2)
    assert out.extra["replan"]["previous_remaining_feasible"] is False
    assert out.feasible, out.infeasible_reasons


def test_sail_track_matches_the_leg_by_leg_march(previous_plan, land_mask, storm_sampler):
    env, spec = make_environment(SHIP, storm_sampler)
    lon, lat, t = previous_plan.track()
    rpm = previous_plan.leg_rpm()
    problem = RouteProblem(lon[0], lat[0], lon[-1], lat[-1], t[0], t[0] + 30 * 86400.0,
                           route_limits(spec))
    march = sail_tracks(problem, env, land_mask, lon[None, :], lat[None, :], rpm[None, :])
    fixed = sail_track(problem, env, land_mask, lon, lat, rpm)
    assert np.max(np.abs(fixed.time_s - march.time_s)) <= 2.0
    assert fixed.fuel_t[0] == pytest.approx(march.fuel_t[0], rel=1e-6)
    assert np.array_equal(fixed.leg_flags, march.leg_flags)
