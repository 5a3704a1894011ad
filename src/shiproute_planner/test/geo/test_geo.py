"""Land mask, geodesy and port gazetteer against known places and brute-force references."""

from __future__ import annotations

import numpy as np
import pytest
from shiproute_core.geodesy import direct, inverse, unwrap_near, wrap_lon
from shiproute_planner.errors import PortNotFoundError, PositionOnLandError
from shiproute_planner.geo.landmask import default_land_mask
from shiproute_planner.geo.ports import lookup_port, resolve_port
from shiproute_planner.geo.raster import COAST, LAND, SEA


@pytest.fixture(scope="module")
def land():
    return default_land_mask()


def test_known_points(land):
    # Seoul, Madrid, Denver on land; mid-Pacific, mid-Atlantic, Indian Ocean at sea
    lon = np.array([126.98, -3.70, -104.99, -150.0, -35.0, 80.0])
    lat = np.array([37.57, 40.42, 39.74, 30.0, 40.0, -20.0])
    assert land.is_land(lon, lat).tolist() == [True, True, True, False, False, False]
    # same points in the continuous frame past 180 deg
    assert land.is_land(lon + 360.0, lat).tolist() == [True, True, True, False, False, False]


def test_raster_agrees_with_exact_polygons(land):
    # brute-force reference: every raster-decided point must match the exact polygon test
    rng = np.random.default_rng(3)
    lon = rng.uniform(-180, 180, 20000)
    lat = rng.uniform(-60, 70, 20000)
    i = ((lat + 90) / land.cell_deg).astype(int)
    j = ((lon + 180) / land.cell_deg).astype(int)
    cls = np.asarray(land.raster)[i, j]
    exact = land.exact.contains(lon, lat)
    assert np.all(exact[cls == LAND])
    assert not np.any(exact[cls == SEA])
    assert (cls == COAST).mean() < 0.1


def test_segments(land):
    # Busan -> Tokyo straight line crosses Japan; a mid-Pacific leg over 180 deg is clear
    hits = land.segment_land_samples(np.array([129.1, 179.0]), np.array([35.1, 30.0]),
                                     np.array([139.7, 181.5]), np.array([35.3, 30.5]))
    assert hits[0] > 0 and hits[1] == 0


def test_geodesy_antimeridian():
    lon, lat = direct(np.array([179.5]), np.array([40.0]), np.array([90.0]), np.array([200e3]))
    assert lon[0] > 180.0  # continues the frame instead of jumping to -180
    az, d = inverse(np.array([179.5]), np.array([40.0]), lon, lat)
    assert d[0] == pytest.approx(200e3, rel=1e-9) and az[0] == pytest.approx(90.0, abs=1e-6)
    assert float(unwrap_near(-118.2, 129.0)) == pytest.approx(241.8)
    assert float(wrap_lon(241.8)) == pytest.approx(-118.2)


def test_ports(land):
    busan = resolve_port("Busan", land)
    assert busan.locode == "KRPUS" and busan.name == "Pusan"
    assert resolve_port("krpus", land) == busan
    assert not land.is_land(np.array([busan.lon_deg]), np.array([busan.lat_deg]))[0]
    assert lookup_port("long beach").locode == "USLGB"
    p = lookup_port("35.08, 129.112")
    assert (p.lat_deg, p.lon_deg) == (35.08, pytest.approx(129.112))
    with pytest.raises(PortNotFoundError, match="Atlantis"):
        lookup_port("Atlantis")
    with pytest.raises(PortNotFoundError, match="out of range"):
        lookup_port("95,10")
    with pytest.raises(PositionOnLandError, match="on land"):
        resolve_port("48.0,10.0", land)  # Bavaria
