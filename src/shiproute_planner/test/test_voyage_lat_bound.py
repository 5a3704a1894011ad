"""The latitude bound follows a voyage's sea lane beyond the default 70 degrees and says so."""

from __future__ import annotations

from datetime import timedelta

from shiproute_planner.geo.ports import lookup_port
from shiproute_planner.plan_setup import route_limits
from shiproute_planner.ship import load_ship
from shiproute_planner.voyage.lat_bound import voyage_lat_bound

NORDKAPP_LAT_DEG = 71.17  # the North Cape; every sea route Tromso -> Murmansk passes north of it


def test_bound_clears_the_north_cape_on_the_way_to_murmansk():
    limits = route_limits(load_ship("container_4600teu"))
    assert limits.lat_bound_deg == 70.0
    widened, notes = voyage_lat_bound(limits, [lookup_port("Tromso"), lookup_port("Murmansk")])
    assert widened.lat_bound_deg > NORDKAPP_LAT_DEG
    assert "sea ice" in notes[0] and "70" in notes[0]


def test_bound_kept_south_of_it_and_when_the_user_set_it():
    limits = route_limits(load_ship("container_4600teu"))
    same, notes = voyage_lat_bound(limits, [lookup_port("Bergen"), lookup_port("Reykjavik")])
    assert same.lat_bound_deg == 70.0 and notes == []
    kept, notes = voyage_lat_bound(limits, [lookup_port("Tromso"), lookup_port("Murmansk")],
                                   fixed=True)
    assert kept.lat_bound_deg == 70.0 and notes == []


def test_tromso_murmansk_plan_is_not_infeasible_for_latitude():
    from shiproute_planner.request import PlanOptions, VoyageRequest, voyage_times

    from shiproute_planner import planning

    depart_s, rta_s = voyage_times("2026-04-01T00:00Z", timedelta(days=2))
    voyage = VoyageRequest("Tromso", "Murmansk", depart_s, rta_s, "container_4600teu")
    plan = planning.plan(voyage, PlanOptions(budget_s=60.0, max_evaluations=1500), None)
    assert not any("latitude" in r for r in plan.infeasible_reasons)
    lat = [w.lat_deg for w in plan.waypoints]
    assert max(lat) > NORDKAPP_LAT_DEG  # round the cape, not over it
    assert any("latitude bound raised" in w for w in plan.warnings)
