"""A kept plan is judged on every optimised span of a leg (`replan_keep.leg_parts`): the
previous plan (Busan -> Long Beach) has two spans with the Tsugaru Strait passage between
them; a re-plan whose voyage does not split at the strait (no computed coastal passages)
holds both in one leg. On forecast cycle 2 the storm sits on the second span: the previous
plan's remainder, marched leg by leg by the test itself, is above the ship's Hs limit there
and below it on the first span. The carried remainder must be judged infeasible (it once
was judged on the first span alone and published as feasible)."""

from __future__ import annotations

import functools
from datetime import timedelta

import numpy as np
import pytest
from shiproute_core.flags import FLAG_WAVE_LIMIT
from shiproute_core.geodesy import unwrap_near
from shiproute_planner.plan_position import position_after
from shiproute_planner.plan_prepare import prepare_voyage
from shiproute_planner.plan_setup import make_environment, route_limits
from shiproute_planner.planning import plan
from shiproute_planner.replan_keep import carried_legs, precheck
from shiproute_planner.request import PlanOptions, VoyageRequest, voyage_times
from shiproute_planner.route.problem import RouteProblem
from shiproute_planner.route.sail import sail_tracks

SHIP = "container_4600teu"
HOURS_ALONG = 6.0  # on the first span, before the strait


def _voyage(coastal_passage: bool = True) -> VoyageRequest:
    depart_s, rta_s = voyage_times("2026-03-03T18:00Z", timedelta(days=13))
    return VoyageRequest("Busan", "Long Beach", depart_s, rta_s, SHIP,
                         coastal_passage=coastal_passage)


@functools.lru_cache(maxsize=1)
def _cycle2():
    from shiproute_weather.sampling.sampler import ForecastSampler
    from shiproute_weather.scenarios.catalogue import scenario_dataset

    return ForecastSampler(scenario_dataset("storm_march_cycle2"))


@pytest.fixture(scope="module")
def previous(land_mask, storm_sampler):
    """Plan 1 on cycle 1 (reproducible: route evaluations), with the strait between spans."""
    out = plan(_voyage(), PlanOptions(land=land_mask, budget_s=600.0, max_evaluations=800,
                                      seed=3), storm_sampler)
    assert out.feasible
    assert len(out.optimised_spans) == 2
    return out


def _marched_hs(previous, position):
    """Hs per leg of the previous plan's remainder marched from `position` on cycle 2, the
    remainder's node index of each leg's start, and the ship's Hs limit."""
    lon, lat, t = previous.track()
    first = int(np.flatnonzero(t > position[2])[0])
    r_lon = np.concatenate([[position[1]], unwrap_near(lon[first:], position[1])])
    r_lat = np.concatenate([[position[0]], lat[first:]])
    env, spec = make_environment(SHIP, _cycle2())
    lim = route_limits(spec)
    problem = RouteProblem(r_lon[0], r_lat[0], r_lon[-1], r_lat[-1], position[2],
                           position[2] + 30 * 86400.0, lim)
    ev = sail_tracks(problem, env, None, r_lon[None, :], r_lat[None, :],
                     previous.leg_rpm()[first - 1:][None, :])
    return ev.legs["hs_m"][0], first, lim.max_hs_m


def test_a_kept_leg_holding_two_spans_is_judged_on_both(previous, land_mask):
    pos = position_after(previous, HOURS_ALONG)
    hs, first, limit_m = _marched_hs(previous, pos)
    (_, b1), (a2, b2) = previous.optimised_spans
    assert first <= b1  # the ship is on the first span
    # remainder legs: leg j starts at previous node first + j - 1 (leg 0 at the ship)
    span1 = hs[:b1 - first + 1]
    span2 = hs[a2 - first + 1:b2 - first + 1]
    assert np.nanmax(span1) <= limit_m  # the first span holds on cycle 2 ...
    assert np.nanmax(span2) > limit_m  # ... the second runs into the storm
    voyage = _voyage(coastal_passage=False)  # one leg: no strait gates in this voyage
    options = PlanOptions(land=land_mask, method="great_circle", previous_plan=previous,
                          position=pos)
    prep = prepare_voyage(voyage, options, _cycle2())
    assert len(prep.ports) == 2 and not prep.strait_legs
    legs = carried_legs(prep, options)
    assert not isinstance(legs, str), legs
    ok, _, _ = precheck(legs, prep)
    assert not ok
    assert int(legs.results[0].flags[0]) & FLAG_WAVE_LIMIT
    # end to end: the great-circle "search" is infeasible too; the remainder is not kept
    out = plan(voyage, options, _cycle2())
    assert out.extra["replan"]["previous_remaining_feasible"] is False
    assert out.extra["replan"]["kept_previous"] is False
