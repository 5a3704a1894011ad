"""A short passage with days to spare: Aberdeen -> Stornoway (a sea lane of ~235 NM round
Duncansby Head and Cape Wrath) with 3 days to its RTA. Even the engine's lowest RPM arrives
a day early, so the fuel-optimal plan sails close to the lane at that RPM and arrives early;
a search whose stages had to fill the 3 days sailed 550-925 NM round the north of Scotland
instead (and arrived late)."""

from __future__ import annotations

import numpy as np
import pyproj
import searoute
from shiproute_planner.geo.ports import resolve_port
from shiproute_planner.plan_request import build_request, run_request


def test_a_short_passage_with_days_to_spare_sails_its_lane_and_arrives_early(land_mask):
    req = build_request(origin="Aberdeen", destination="Stornoway", depart="2026-06-01T00:00Z",
                        rta="3d", budget="3000ev", seed=1)
    plan = run_request(req)
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
