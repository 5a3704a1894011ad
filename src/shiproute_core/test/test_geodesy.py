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


def test_cross_track_against_the_nearest_point_of_the_geodesic() -> None:
    # the Aviation Formulary's example (Williams): course LAX (33deg57'N 118deg24'W) -> JFK
    # (40deg38'N 73deg47'W), ship at D (34deg30'N 116deg30'W), right of course. Reference: the
    # shortest WGS 84 distance from D to the geodesic, by brute force over 20,001 points on it
    lax = (-(118 + 24 / 60), 33 + 57 / 60)
    jfk = (-(73 + 47 / 60), 40 + 38 / 60)
    lon, lat = geodesy.great_circle_points(*lax, *jfk, 20_001)
    nearest = geodesy.distance_m(np.full(lon.size, -116.5), np.full(lon.size, 34.5), lon, lat)
    xtd = geodesy.cross_track_m(np.array([-116.5]), np.array([34.5]), *lax, *jfk)
    assert xtd[0] > 0  # right of course
    assert xtd[0] == pytest.approx(nearest.min(), abs=20.0)
    # mirrored across the equator the course turns the other way: the point is left of it
    xtd_south = geodesy.cross_track_m(np.array([-116.5]), np.array([-34.5]), lax[0], -lax[1],
                                      jfk[0], -jfk[1])
    assert xtd_south[0] == pytest.approx(-xtd[0], rel=1e-9)


def test_points_on_the_great_circle_have_no_cross_track() -> None:
    lon, lat = geodesy.great_circle_points(129.0, 35.0, 241.7, 33.7, 9)
    xtd = geodesy.cross_track_m(lon[1:-1], lat[1:-1], 129.0, 35.0, 241.7, 33.7)
    # WGS 84 geodesic vs the spherical great circle: well under a kilometre on 5,000 NM
    assert np.all(np.abs(xtd) < 1000.0)


def test_track_length_adds_up_to_the_quarter_meridian() -> None:
    # WGS 84 quarter meridian 10,001,965.729 m, here as ten legs along the meridian
    lat = np.linspace(0.0, 90.0, 11)
    assert geodesy.track_length_m(np.zeros(11), lat) == pytest.approx(10_001_965.729, abs=0.01)


def test_distance_within_agrees_with_the_geodesic_on_every_side_of_its_threshold() -> None:
    # points at every latitude and bearing, 0-40 NM from the target: the threshold test
    # (<= 10 NM) must come out as the WGS 84 geodesic says, near or far, poles included
    rng = np.random.default_rng(7)
    for lat1 in (0.0, 45.0, 89.5, -60.0):
        n = 4000
        lon, lat = geodesy.direct(np.full(n, 10.0), np.full(n, lat1), rng.uniform(0, 360, n),
                                  rng.uniform(0.0, 40.0 * M_PER_NM, n))
        exact = geodesy.distance_m(lon, lat, np.full(n, 10.0), np.full(n, lat1))
        got = geodesy.distance_within_m(lon, lat, 10.0, lat1, 10.0 * M_PER_NM)
        assert np.array_equal(got <= 10.0 * M_PER_NM, exact <= 10.0 * M_PER_NM)
        near = exact <= 10.0 * M_PER_NM
        np.testing.assert_allclose(got[near], exact[near], rtol=0, atol=1e-6)
        assert got.shape == (n,)
    grid = geodesy.distance_within_m(np.zeros((3, 2)), np.ones((3, 2)), 0.0, 1.0, 1000.0)
    assert grid.shape == (3, 2) and np.all(grid == 0.0)
