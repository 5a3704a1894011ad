"""A short passage with days to spare: Aberdeen -> Stornoway (a sea lane of ~235 NM round
Duncansby Head and Cape Wrath) with 3 days to its RTA. Even the engine's lowest RPM arrives
a day early, so the fuel-optimal plan sails close to the lane at that RPM, arrives early and
says why. Its departure passage ends in Peterhead's harbour basin behind breakwaters, where
the sea lane's network node lies: before the passage learnt to end in the water nearest to
it, the lane was sailed across the Buchan coast and the plan was infeasible."""

from __future__ import annotations

import numpy as np
import pyproj
import searoute
from shiproute_planner.geo.ports import resolve_port
from shiproute_planner.plan_request import build_request, run_request


def test_a_short_passage_with_days_to_spare_sails_its_lane_and_arrives_early(land_mask):
    req = build_request(origin="Aberdeen", destination="Stornoway", depart="2026-06-01T00:00Z",
                        rta="3d", budget="3000ev", seed=1)
    plan = run_request(req, with_baseline=False)  # the search's own route, not the lane's
    assert plan.feasible, plan.infeasible_reasons
    assert plan.eta_s <= plan.rta_s - 12 * 3600.0  # early: the lowest RPM needs ~1.5 days
    # the sea lane's length from searoute itself, between the ports the plan resolved
    a, b = resolve_port("Aberdeen", land_mask), resolve_port("Stornoway", land_mask)
    lane = np.asarray(searoute.searoute([a.lon_deg, a.lat_deg], [b.lon_deg, b.lat_deg])
                      ["geometry"]["coordinates"], dtype=float)
    geod = pyproj.Geod(ellps="WGS84")
    _, _, hops = geod.inv(lane[:-1, 0], lane[:-1, 1], lane[1:, 0], lane[1:, 1])
    lane_nm = float(np.sum(hops)) / 1852.0
    # the search spans 1.1 times the lane at the lowest RPM; clearance and the ports'
    # passages add a few miles more
    assert plan.total_distance_nm <= 1.2 * lane_nm
    assert any("arrives early" in w for w in plan.warnings)


def test_the_search_spans_no_more_than_the_lowest_rpm_needs(land_mask):
    # Genoa -> Barcelona (~370 NM of sea lane) with 5 days: at its lowest RPM (~7 kn) the ship
    # needs about 2 days; stages spanning all 5 would make the GA's routes sail round to fill
    # them, so the stages span at most the lowest RPM's time over 1.1 times the lane
    from shiproute_planner.plan_setup import make_environment, route_limits
    from shiproute_planner.route.voyage_legs import leg_setup
    from shiproute_planner.ship import SeaState

    env, spec = make_environment("container_4600teu")
    a, b = resolve_port("Genoa", land_mask), resolve_port("Barcelona", land_mask)
    t0 = 1.78e9
    setup = leg_setup(a, b, env, route_limits(spec), land_mask, t0, t0 + 5 * 86400.0)
    p = setup.problem
    lane = np.asarray(searoute.searoute([a.lon_deg, a.lat_deg], [b.lon_deg, b.lat_deg])
                      ["geometry"]["coordinates"], dtype=float)
    _, _, hops = pyproj.Geod(ellps="WGS84").inv(lane[:-1, 0], lane[:-1, 1], lane[1:, 0],
                                                lane[1:, 1])
    slowest = env.model.evaluate(np.array([spec.engine.rpm_min]), np.zeros(1), SeaState.calm(1))
    slowest_s = 1.1 * float(np.sum(hops)) / float(slowest.stw_m_s[0])
    assert p.n_stages > 0
    assert p.n_stages * p.stage_s <= slowest_s + p.stage_s
    assert p.n_stages * p.stage_s < 0.6 * (p.rta_s - p.depart_s)  # well inside the window
    assert any("arrives early" in n for n in setup.notes)
