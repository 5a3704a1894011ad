"""Ports that resolve: aliases, UN/LOCODEs, river ports at their seaward end, suggestions."""

from __future__ import annotations

import numpy as np
import pytest
from shiproute_core.geodesy import inverse
from shiproute_core.units import M_PER_NM
from shiproute_planner.errors import PortNotFoundError
from shiproute_planner.geo.ports import lookup_port, resolve_port


def _on_full_land(lon_deg: float, lat_deg: float) -> bool:
    """Independent reference: the point lies inside a GSHHG full-resolution land polygon
    (shapely on the polygons' rings, not the planner's rasters)."""
    import shapely
    from shiproute_planner.geo.gshhg import load_land_polygons

    polygons = load_land_polygons("f")
    b = polygons.bounds
    near = np.flatnonzero((b[:, 0] <= lon_deg) & (b[:, 2] >= lon_deg)
                          & (b[:, 1] <= lat_deg) & (b[:, 3] >= lat_deg))
    point = shapely.Point(lon_deg, lat_deg)
    return any(shapely.Polygon(polygons.ring(int(i))).contains(point) for i in near)


@pytest.mark.parametrize(("typed", "locode"), [
    ("Genoa", "ITGOA"), ("Genova", "ITGOA"), ("Hamilton", "BMBDA"), ("Bermuda", "BMBDA"),
    ("Naples", "ITNAP"), ("Antwerp", "BEANR"), ("Gothenburg", "SEGOT"), ("itgoa", "ITGOA"),
    ("DE HAM", "DEHAM"), ("Algiers", "DZALG"), ("Nantes", "FRMTX"), ("Gqeberha", "ZAPLZ"),
    ("Glasgow", "GBGRK"), ("Athens", "GRPIR"),
])
def test_aliases_and_locodes(typed, locode):
    assert lookup_port(typed).locode == locode


@pytest.mark.parametrize(("name", "sea_end", "max_nm"), [
    # city positions are 40-290 NM up their rivers; the plan must start near the mouth
    ("Houston", (29.33, -94.70), 10), ("Hamburg", (53.95, 8.30), 15),
    ("Antwerp", (51.42, 3.50), 15), ("Montreal", (48.30, -69.40), 15),
    ("Portland", (46.25, -124.08), 10),  # Columbia River entrance between the jetties
    # river mouths' landmarks: Elephant Point (Yangon River), Patenga (Karnaphuli), the Humen
    # narrows (Pearl River); the pilot areas lie seaward of them
    ("Yangon", (16.48, 96.32), 15), ("Chittagong", (22.23, 91.79), 10),
    ("Guangzhou", (22.80, 113.65), 20),
])
def test_river_ports_start_at_sea_and_say_so(land_mask, name, sea_end, max_nm):
    port = resolve_port(name, land_mask)
    _, d = inverse(port.lon_deg, port.lat_deg, sea_end[1], sea_end[0])
    assert float(d) / M_PER_NM < max_nm
    assert not land_mask.is_land([port.lon_deg], [port.lat_deg])[0]
    assert "seaward end" in port.note and "pilotage" in port.note


def test_unknown_name_suggests_close_matches():
    with pytest.raises(PortNotFoundError, match=r"similar names: .*rotterdam"):
        lookup_port("Roterdam")
    with pytest.raises(PortNotFoundError, match=r"genova|genoa"):
        lookup_port("Genua")


def test_every_alias_names_a_gazetteer_port():
    # an alias to a name the gazetteer lacks makes a port that exists unreachable
    from shiproute_planner.geo.port_aliases import ALIASES
    from shiproute_planner.geo.ports import _gazetteer

    by_name, _ = _gazetteer()
    assert sorted(k for k, v in ALIASES.items() if v not in by_name) == []


@pytest.mark.parametrize(("typed", "locode"), [
    # the gazetteer spells these with a qualifier, another spelling or an accent
    ("Seattle", "USSEA"), ("Cebu", "PHCEB"), ("Venice", "ITVCE"), ("Dunkirk", "FRDKK"),
    ("Zeebrugge", "BEZEE"), ("Ålesund", "NOAES"), ("Málaga", "ESAGP"), ("Makassar", "IDMAC"),
    ("Kuantan", "MYKUA"),
])
def test_common_names_reach_qualified_or_respelled_entries(typed, locode):
    assert lookup_port(typed).locode == locode


@pytest.mark.parametrize(("typed", "city"), [
    # published city positions: Portland, Oregon and Portland, Maine
    ("USPDX", (45.52, -122.68)), ("USPWM", (43.66, -70.25)),
])
def test_locode_resolves_to_its_own_city(typed, city):
    port = lookup_port(typed)
    lat = port.berth_lat_deg if port.is_river_port else port.lat_deg
    lon = port.berth_lon_deg if port.is_river_port else port.lon_deg
    _, d = inverse(lon, lat, city[1], city[0])
    assert float(d) < 15_000.0


def test_a_name_shared_by_ports_far_apart_says_which_was_chosen():
    note = lookup_port("Portland").note
    # Portland, Maine; Portland, Victoria; Portland, Dorset are other ports of that name
    assert "USPWM" in note and "AUPTJ" in note and "GBPTL" in note and "UN/LOCODE" in note
    assert lookup_port("Genoa").note == ""  # one port of that name: nothing to say


@pytest.mark.parametrize(("name", "up_river_nm"), [
    # berths up rivers and ship canals, far from water the coastline data resolves: the
    # published river passages are ~65 NM up the Seine, ~125 NM up the Hooghly, ~50 NM up
    # the Guadalquivir, ~36 NM through the Manchester Ship Canal and Mersey, ~85 NM up the
    # Columbia, ~45 NM up the Saigon River and Long Tau channel; Stockholm's fairway through
    # the archipelago to Sandhamn is ~40 NM, with passages (Oxdjupet, ~150 m) narrower than
    # the 0.1 NM passage grid
    ("Rouen", 65), ("Kolkata", 125), ("Sevilla", 50), ("Manchester", 36), ("Portland", 85),
    ("Ho Chi Minh City", 45), ("Stockholm", 40),
])
def test_ports_up_rivers_resolve_at_sea_at_full_resolution(land_mask, name, up_river_nm):
    port = resolve_port(name, land_mask)
    assert port.is_river_port and "seaward end" in port.note
    assert not _on_full_land(port.lon_deg, port.lat_deg)
    _, d = inverse(port.lon_deg, port.lat_deg, port.berth_lon_deg, port.berth_lat_deg)
    # the straight line is shorter than the winding river, and not absurdly so
    assert 0.3 * up_river_nm < float(d) / M_PER_NM < 1.2 * up_river_nm


@pytest.mark.parametrize(("name", "landmark", "max_nm"), [
    # ports up rivers with no entry in the river-port table, found along the sea lane; the
    # landmarks are the rivers' mouths or estuaries: Tybee Island light (Savannah River),
    # Sabine Pass (Sabine-Neches Waterway), Chipiona (Guadalquivir), Pauillac (Gironde),
    # Phra Samut Chedi (Chao Phraya), Astoria (Columbia), Buenos Aires (Rio de la Plata)
    ("Savannah", (32.02, -80.85), 5), ("Beaumont", (29.73, -93.87), 10),
    ("Seville", (36.74, -6.43), 10), ("Bordeaux", (45.20, -0.75), 20),
    ("Bangkok", (13.60, 100.58), 10), ("Longview", (46.19, -123.83), 25),
    ("Rosario", (-34.60, -58.37), 30),
])
def test_ports_up_unlisted_rivers_start_where_the_lane_reaches_resolved_water(
        land_mask, name, landmark, max_nm):
    from shiproute_planner.geo.port_aliases import RIVER_PORTS
    from shiproute_planner.river_passages import RIVER_TRANSIT_KN, river_passage

    port = resolve_port(name, land_mask)
    assert port.locode not in RIVER_PORTS  # found, not looked up
    assert port.is_river_port and "seaward end" in port.note and "pilotage" in port.note
    _, d = inverse(port.lon_deg, port.lat_deg, landmark[1], landmark[0])
    assert float(d) / M_PER_NM < max_nm
    assert not _on_full_land(port.lon_deg, port.lat_deg)  # an independent polygon test
    # the river passage is timed: at least the straight line from the berth at 10 kn (the
    # lane's ends are rounded to 1e-4 deg, ~10 m, so within 0.1 % of it)
    passage = river_passage(port)
    _, straight = inverse(port.lon_deg, port.lat_deg, port.berth_lon_deg, port.berth_lat_deg)
    assert passage is not None
    assert passage.hours >= 0.999 * float(straight) / M_PER_NM / RIVER_TRANSIT_KN


@pytest.mark.parametrize("name", [
    # Wuhan lies ~500 NM up the Yangtze; the lane network's nearest node is at its mouth
    "Wuhan",
    # on the Caspian: the lane network leads ~980 NM up the Volga and through the Volga-Don
    # canal (locks for ships under ~140 m) to the Sea of Azov
    "Turkmenbasy",
])
def test_a_port_no_river_passage_reaches_asks_for_its_seaward_end(land_mask, name):
    from shiproute_planner.errors import PositionOnLandError

    with pytest.raises(PositionOnLandError, match=rf"{name}.*seaward end as 'lat,lon'"):
        resolve_port(name, land_mask)


def test_a_terminal_near_water_is_snapped_not_made_a_river_port(land_mask):
    # Ras Tanura's gazetteer position is 2.5 km inland of its own pier head
    port = resolve_port("Ras Tanura", land_mask)
    assert not port.is_river_port and 0.0 < port.snapped_km <= 5.0
