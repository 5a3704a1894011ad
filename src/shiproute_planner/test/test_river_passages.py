"""River ports: the river passage between the channel's seaward end and the berth gets its
time in the voyage (departure from the seaward end later, arrival there earlier than the
berth RTA), and the plan says so. Checked on river ports outside the world lane set
(New Orleans, Philadelphia, Houston)."""

from __future__ import annotations

import pytest
from shiproute_planner.geo.ports import Port, lookup_port
from shiproute_planner.river_passages import (
    RIVER_TRANSIT_KN,
    river_calls,
    river_passage,
    river_times,
)
from shiproute_planner.voyage.port_calls import PortCall

# River distances from published figures (independent of the sea lane): New Orleans lies at
# mile 95 of the Mississippi above Head of Passes and Southwest Pass runs ~17.5 NM below it
# to the sea buoy (US Army Corps of Engineers river miles: ~83 + 17.5 ~ 100 NM); the
# Delaware is ~85 NM from the capes to Philadelphia (Pilots' Association for the Bay and
# River Delaware). The sea lane may bend more than the river's centreline: 20 % slack above,
# 10 % below.
PUBLISHED_NM = {"New Orleans": 100.0, "Philadelphia": 85.0}


@pytest.mark.parametrize("name", sorted(PUBLISHED_NM))
def test_river_passage_length_matches_the_published_river_distance(name):
    port = lookup_port(name)
    assert port.is_river_port
    rp = river_passage(port)
    assert rp is not None
    assert 0.9 * PUBLISHED_NM[name] <= rp.length_nm <= 1.2 * PUBLISHED_NM[name]
    assert rp.hours == pytest.approx(rp.length_nm / RIVER_TRANSIT_KN)


def test_a_port_at_sea_has_no_river_passage():
    assert river_passage(lookup_port("Singapore")) is None
    assert river_passage(Port("33.0,-120.0", "", 33.0, -120.0)) is None


def test_voyage_times_give_both_river_passages_their_time():
    a, b = lookup_port("New Orleans"), lookup_port("Houston")
    ra, rb = river_passage(a), river_passage(b)
    depart, rta = 1_780_000_000.0, 1_780_000_000.0 + 3 * 86400.0
    dep, arr, notes, rows = river_times(a, b, depart, rta)
    assert dep == pytest.approx(depart + ra.length_nm / RIVER_TRANSIT_KN * 3600.0)
    assert arr == pytest.approx(rta - rb.length_nm / RIVER_TRANSIT_KN * 3600.0)
    assert len(notes) == 2 and "New Orleans" in notes[0] and "Houston" in notes[1]
    assert [r["end"] for r in rows] == ["departure", "arrival"]
    # a port at sea at either end changes nothing
    sea = lookup_port("Singapore")
    assert river_times(sea, sea, depart, rta)[:2] == (depart, rta)


def test_a_river_call_moves_its_window_to_the_seaward_end_and_stays_longer():
    port = lookup_port("Philadelphia")
    rp = river_passage(port)
    call = PortCall(port.name, 100_000.0, 200_000.0, 7200.0)
    (out,), notes, _ = river_calls([port], [call])
    assert out.latest_s == pytest.approx(200_000.0 - rp.seconds)
    assert out.earliest_s == pytest.approx(100_000.0 - rp.seconds)
    assert out.berth_s == pytest.approx(7200.0 + 2 * rp.seconds)
    (free,), _, _ = river_calls([port], [None])
    assert free.berth_s == pytest.approx(2 * rp.seconds) and free.latest_s is None
    assert notes and "Philadelphia" in notes[0]


@pytest.mark.slow
def test_plan_between_river_ports_is_timed_to_the_berths():
    from datetime import timedelta

    from shiproute_planner.planning import plan_voyage

    depart = "2026-05-01T00:00Z"
    plan = plan_voyage("New Orleans", "Houston", depart, timedelta(days=2),
                       "container_4600teu", budget_s=2.0)
    rows = {r["end"]: r for r in plan.extra["river_passages"]}
    t0 = 1_777_593_600.0  # 2026-05-01T00:00Z
    assert plan.departure_s == pytest.approx(t0 + rows["departure"]["hours"] * 3600.0)
    assert plan.rta_s == pytest.approx(t0 + 2 * 86400.0 - rows["arrival"]["hours"] * 3600.0)
    assert plan.feasible, plan.infeasible_reasons
    # on time at the berth: the seaward end reached the river passage before the RTA
    assert rows["arrival"]["berth_eta_s"] <= t0 + 2 * 86400.0 + 300.0
    timed = [w for w in plan.warnings if "river passage" in w and " takes " in w]
    assert len(timed) == 2 and "New Orleans" in timed[0] and "Houston" in timed[1]
