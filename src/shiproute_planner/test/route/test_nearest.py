"""The nearest node of a polyline by spherical pre-selection is the one a geodesic to every
node finds (brute force on WGS 84), with the same distance and the same 'too far' verdict."""

from __future__ import annotations

import numpy as np
from shiproute_core.geodesy import inverse
from shiproute_planner.route.nearest import nearest_node


def _brute(lon, lat, to_lon, to_lat, within_m):
    _, d = inverse(lon, lat, np.full(lon.size, to_lon), np.full(lon.size, to_lat))
    d = np.atleast_1d(np.asarray(d))
    return None if d.min() > within_m else (int(np.argmin(d)), float(d.min()))


def test_nearest_node_agrees_with_a_geodesic_to_every_node() -> None:
    rng = np.random.default_rng(7)
    for case in range(40):
        n = int(rng.integers(1, 1200))
        if case % 2:  # a densified lane, as the strait and canal search sees it
            lon = np.linspace(rng.uniform(-180, 0), rng.uniform(0, 180), n)
            lat = np.linspace(rng.uniform(-80, 0), rng.uniform(0, 80), n)
        else:
            lon, lat = rng.uniform(-180, 180, n), rng.uniform(-85, 85, n)
        to_lon, to_lat = rng.uniform(-180, 180), rng.uniform(-85, 85)
        d_min = _brute(lon, lat, to_lon, to_lat, np.inf)[1]
        # unbounded, a lane passing 25 km off, and just inside / just outside the nearest
        for within in (np.inf, 25_000.0, d_min * 1.0005, d_min * 0.9995):
            got = nearest_node(lon, lat, to_lon, to_lat, within)
            want = _brute(lon, lat, to_lon, to_lat, within)
            assert (got is None) == (want is None), (case, within)
            if want is not None:
                assert got[0] == want[0] and abs(got[1] - want[1]) < 1e-6


def test_nearest_node_of_a_point_on_the_line_is_that_point() -> None:
    # the Tsugaru Strait's western gate sitting on a densified lane node
    lon = np.linspace(139.0, 142.0, 301)
    lat = np.full(301, 41.3)
    assert nearest_node(lon, lat, float(lon[120]), 41.3, 25_000.0) == (120, 0.0)
    assert nearest_node(lon, lat, 140.5, 41.6, 25_000.0) is None  # 33 km north of the lane
