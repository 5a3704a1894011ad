"""WGS 84 geodesy against published geodesic figures and the ellipsoid's own definition."""

from __future__ import annotations

import numpy as np
import pytest
from shiproute_core.units import M_PER_NM, M_S_PER_KNOT

from shiproute_core import geodesy


def test_one_minute_of_latitude_is_about_a_nautical_mile() -> None:
    # on WGS 84 one arc-minute of latitude runs from 1842.9 m (equator) to 1861.6 m (pole)
    at_equator = geodesy.distance_m(0.0, 0.0, 0.0, 1 / 60)
    at_pole = geodesy.distance_m(0.0, 90 - 1 / 60, 0.0, 90.0)
    assert at_equator == pytest.approx(1842.9, abs=0.2)
    assert at_pole == pytest.approx(1861.6, abs=0.2)


def test_quarter_meridian_length() -> None:
    # WGS 84 quarter meridian: 10,001,965.729 m
    assert geodesy.distance_m(0.0, 0.0, 0.0, 90.0) == pytest.approx(10_001_965.729, abs=0.01)


def test_equatorial_degree_and_bearings() -> None:
    # one degree of longitude on the equator = a * pi / 180 with a = 6,378,137 m
    one_degree = 6_378_137 * np.pi / 180
    assert geodesy.distance_m(0.0, 0.0, 1.0, 0.0) == pytest.approx(one_degree, abs=1e-3)
    assert geodesy.bearing_deg(0.0, 0.0, 1.0, 0.0) == pytest.approx(90.0)
    assert geodesy.bearing_deg(0.0, 0.0, 0.0, 1.0) == pytest.approx(0.0)
    assert geodesy.bearing_deg(10.0, 10.0, 10.0, 9.0) == pytest.approx(180.0)


def test_destination_inverts_distance_and_wraps_the_antimeridian() -> None:
    lon, lat = geodesy.destination(179.5, 10.0, 90.0, 200_000.0)
    assert -180.0 <= float(lon) < 180.0 and float(lon) < -178.0
    assert geodesy.distance_m(179.5, 10.0, lon, lat) == pytest.approx(200_000.0, abs=1e-3)


def test_knot_is_a_nautical_mile_per_hour() -> None:
    assert M_PER_NM == 1852.0
    assert pytest.approx(1852.0) == M_S_PER_KNOT * 3600.0
