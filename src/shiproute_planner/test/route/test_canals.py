"""Canals as fixed passages: lanes through Suez and Panama use them when the ship fits the
authorities' limits and go round (Cape of Good Hope, Cape Horn) when it does not."""

from __future__ import annotations

import dataclasses
import itertools

import numpy as np
import pytest
from shiproute_core.geodesy import inverse
from shiproute_core.units import M_PER_NM
from shiproute_planner.geo.ports import lookup_port
from shiproute_planner.plan_setup import make_environment, route_limits
from shiproute_planner.route.canals import CANALS, route_canals, sail_canal
from shiproute_planner.ship import load_ship


def _ship(draft_m: float | None = None):
    spec = load_ship("container_4600teu")
    if draft_m is None:
        return spec
    cond = dataclasses.replace(spec.condition, draft_fore_m=draft_m, draft_aft_m=draft_m)
    return dataclasses.replace(spec, condition=cond)


def test_singapore_rotterdam_goes_through_suez():
    ports, legs, _, notes = route_canals([lookup_port("Singapore"), lookup_port("Rotterdam")],
                                         _ship(), [])
    names = [p.name for p in ports]
    assert names[1:3] == ["Suez Canal entrance", "Suez Canal exit"]
    assert legs[1][0].name == "Suez Canal" and not legs[1][1]  # south to north
    assert any("Suez Canal: transit" in n for n in notes)


def test_ship_over_suez_limits_goes_round_the_cape():
    # SCA: 66 ft (20.1 m) maximum draft; a 21.5 m draft is over it
    ports, legs, _, notes = route_canals([lookup_port("Singapore"), lookup_port("Rotterdam")],
                                         _ship(21.5), [])
    assert not legs
    via = ports[1]
    assert via.lat_deg < -34.8  # south of Africa (Cape Agulhas is at 34.83 S)
    assert "draft 21.5 m > 20.1 m" in notes[0]


def test_panama_neopanamax_limits():
    ny, la = lookup_port("New York"), lookup_port("Los Angeles")
    _, legs, _, _ = route_canals([ny, la], _ship(), [])
    assert [c.name for c, _ in legs.values()] == ["Panama Canal (Neopanamax locks)"]
    ports, legs, _, notes = route_canals([ny, la], _ship(15.5), [])  # > 15.2 m TFW
    # round the Horn (turning points before it keep the lanes off the isthmus)
    assert not legs and any(p.lat_deg < -55.9 for p in ports[1:-1]) and "Cape Horn" in notes[0]


def test_canal_transit_time_and_no_land_check():
    suez = next(c for c in CANALS if c.name == "Suez Canal")
    env, spec = make_environment("container_4600teu", None)
    lim = route_limits(spec)
    lead_in, ev, lead_out, _rpm, _ = sail_canal(env, suez, False, 0.0, lim, 43200.0)
    lon, lat = ev.lon_deg[0], ev.lat_deg[0]
    _, seg = inverse(lon[:-1], lat[:-1], lon[1:], lat[1:])
    hours = float(ev.eta_s[0] - ev.time_s[0, 0]) / 3600.0
    # 7.5 kn over the canal line (Suez Bay to off Port Said, ~105 NM): ~14 h
    assert hours == pytest.approx(np.sum(seg) / M_PER_NM / 7.5, rel=0.03)
    assert int(ev.flags[0]) == 0 and lead_in is not None and lead_out is None


def test_ship_over_panama_limits_keeps_clear_of_the_isthmus_on_every_lane():
    # the shortest lane from the Gulf of Mexico to Cape Horn runs through Panama, so a turning
    # point at the Horn alone would send a ship too big for the locks across the isthmus
    from pyproj import Geod
    from shiproute_planner.geo.sea_lanes import sea_lane_between

    ports, legs, _, notes = route_canals([lookup_port("Houston"), lookup_port("Busan")],
                                         _ship(15.5), [])  # > 15.2 m TFW
    assert not legs and "Cape Horn" in notes[0]
    geod = Geod(ellps="WGS84")
    for a, b in itertools.pairwise(ports):
        lane = sea_lane_between(a.lon_deg, a.lat_deg, b.lon_deg, b.lat_deg)
        _, _, d = geod.inv(np.full(len(lane), -79.7), np.full(len(lane), 9.1),
                           lane[:, 0], lane[:, 1])
        assert d.min() > 300_000.0, (a.name, b.name)  # Gatun Lake is at 9.1 N, 79.7 W


@pytest.mark.parametrize(("origin", "destination", "canal_end"), [
    # Ain Sokhna lies on the Gulf of Suez ~20 NM south of Port Tewfik, the canal's southern
    # end; its transit joins the line there, not 150 NM south at the gulf's mouth
    ("Ain Sokhna", "Rotterdam", "entrance"), ("Rotterdam", "Ain Sokhna", "exit"),
])
def test_a_port_beside_a_canals_lead_in_joins_its_line_nearby(origin, destination, canal_end):
    a, b = lookup_port(origin), lookup_port(destination)
    ports, legs, _, _ = route_canals([a, b], _ship(), [])
    gulf_port = a if canal_end == "entrance" else b
    end = next(p for p in ports if p.name == f"Suez Canal {canal_end}")
    _, d = inverse(gulf_port.lon_deg, gulf_port.lat_deg, end.lon_deg, end.lat_deg)
    assert float(d) / M_PER_NM < 30.0
    canal, _ = next(iter(legs.values()))
    tewfik, port_said = (29.93, 32.57), (31.26, 32.31)  # the canal proper stays whole
    for lat, lon in (tewfik, port_said):
        assert min(abs(p[0] - lat) + abs(p[1] - lon) for p in canal.line) < 1e-9
