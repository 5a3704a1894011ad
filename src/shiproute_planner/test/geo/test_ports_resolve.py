"""Ports that resolve: aliases, UN/LOCODEs, river ports at their seaward end, suggestions."""

from __future__ import annotations

import pytest
from shiproute_core.geodesy import inverse
from shiproute_core.units import M_PER_NM
from shiproute_planner.errors import PortNotFoundError
from shiproute_planner.geo.ports import lookup_port, resolve_port


@pytest.mark.parametrize(("typed", "locode"), [
    ("Genoa", "ITGOA"), ("Genova", "ITGOA"), ("Hamilton", "BMBDA"), ("Bermuda", "BMBDA"),
    ("Naples", "ITNAP"), ("Antwerp", "BEANR"), ("Gothenburg", "SEGOT"), ("itgoa", "ITGOA"),
    ("DE HAM", "DEHAM"),
])
def test_aliases_and_locodes(typed, locode):
    assert lookup_port(typed).locode == locode


@pytest.mark.parametrize(("name", "sea_end", "max_nm"), [
    # city positions are 40-290 NM up their rivers; the plan must start near the mouth
    ("Houston", (29.33, -94.70), 10), ("Hamburg", (53.95, 8.30), 15),
    ("Antwerp", (51.42, 3.50), 15), ("Montreal", (48.30, -69.40), 15),
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
