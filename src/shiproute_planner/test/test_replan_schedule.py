"""A re-plan under way schedules its legs from where the ship is (`voyage.legs`): searoute
snaps a position at sea to its network's nearest node, which for the demo's replayed ship
27 h out of Busan (39.71N 136.65E, bound for the Tsugaru Strait) lies behind it at 41.77N
135.96E; the first leg's length came out 315 NM for ~183 NM of open water, the schedule had
the ship dawdle to the strait, and beyond it cycle 2's storm caught every plan (a cold plan
from there with 20,000 route evaluations too: Hs 9 m against 8 m). The way ahead is now the
open-water hop onto the lane where hop and lane are shortest."""

from __future__ import annotations

import numpy as np
import pyproj
from shiproute_core.units import M_PER_NM
from shiproute_planner.planning import plan
from shiproute_planner.request import PlanOptions, VoyageRequest, voyage_times
from shiproute_planner.voyage.legs import sea_distance_under_way_m

SHIP_27H = (39.7117, 136.6502)  # the replayed ship (constant-RPM baseline) 27 h out
TSUGARU_WEST_GATE = (41.45, 139.95)


def test_a_ship_at_sea_joins_the_lane_ahead_of_it(land_mask):
    (lat0, lon0), (lat1, lon1) = SHIP_27H, TSUGARU_WEST_GATE
    _, _, direct_m = pyproj.Geod(ellps="WGS84").inv(lon0, lat0, lon1, lat1)
    got = sea_distance_under_way_m(land_mask, lon0, lat0, lon1, lat1)
    # open water all the way (the Sea of Japan): the great circle, give or take a lane bend
    assert direct_m <= got + 1.0
    assert got <= 1.05 * direct_m, (got / M_PER_NM, direct_m / M_PER_NM)


def test_the_demo_re_plan_27_h_out_on_cycle_2_is_feasible(land_mask):
    from shiproute_weather.sampling.sampler import ForecastSampler
    from shiproute_weather.scenarios.catalogue import scenario_dataset

    cycle2 = ForecastSampler(scenario_dataset("storm_march_cycle2"), dtype=np.float16)
    depart_s, rta_s = voyage_times("2026-03-03T18:00:00Z", "2026-03-16T18:00:00Z")
    voyage = VoyageRequest("Busan", "Long Beach", depart_s, rta_s, "container_4600teu")
    # 12,000 evaluations (what ~4 s buy on an idle 2-core machine): at the 2-NM open-sea
    # clearance 6,000 left this re-plan 3.5 h early (seed 0) or in the storm (seed 1)
    out = plan(voyage, PlanOptions(land=land_mask, budget_s=600.0, max_evaluations=12_000,
                                   seed=0, position=(*SHIP_27H, depart_s + 27 * 3600.0)),
               cycle2)
    assert out.feasible, out.infeasible_reasons
    assert abs(out.eta_s - rta_s) <= 3600.0
