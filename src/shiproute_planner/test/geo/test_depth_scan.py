"""The optimiser's capped depth scan (open water crossed in clear-distance jumps, legs over
threads) gives the plain walk's result, and its verdict is the brute-force one: the
shallowest of every sample along the leg; a route's legs scan as they do one by one."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from shiproute_planner.geo import _depth_kernels as dk
from shiproute_planner.geo.bathymetry import default_depth_files
from shiproute_planner.geo.depth import load_bathymetry
from shiproute_planner.geo.depth_scan import LEVELS_M, capped_min_depth_m, level_for
from shiproute_planner.geo.land_kernels import segment_ends

SKERKI = Path(__file__).parents[1] / "data" / "skerki_etopo2022_30s.nc"


def _legs(rng: np.random.Generator, centres: list[tuple[float, float]], per: int,
          reach_deg: float) -> tuple[np.ndarray, ...]:
    """Random legs of up to `reach_deg` round each centre (lon, lat)."""
    out = []
    for c_lon, c_lat in centres:
        a = rng.uniform(-reach_deg, reach_deg, (4, per))
        out.append((c_lon + a[0], c_lat + 0.5 * a[1], c_lon + a[2], c_lat + 0.5 * a[3]))
    return tuple(np.concatenate([o[k] for o in out]) for k in range(4))


def _check(bathy, legs, cap) -> None:
    got = capped_min_depth_m(bathy, *legs, cap)
    plain = bathy.segment_min_depth_m(*legs, cap)
    # the same samples decide the shallows; NaN (no depth met) and the cap (no shallows
    # met) may swap where the jumps cross water the plain walk touched, and on no more than
    # a few legs
    assert np.array_equal(np.where(np.isnan(got), cap, got), np.where(np.isnan(plain), cap,
                                                                       plain))
    assert np.mean(np.isnan(got) != np.isnan(plain)) < 0.02
    # brute force: the shallowest of every sample (no cap, no skipping)
    every = bathy.segment_min_depth_m(*legs, np.inf)
    shallow = every < cap
    assert 0.1 < shallow.mean() < 0.9  # both kinds of legs in the sample
    assert np.array_equal(got < cap, shallow)
    assert np.array_equal(got[shallow], every[shallow])


@pytest.mark.skipif(not default_depth_files(), reason="ETOPO5 (ferret-datasets) not installed")
def test_global_capped_scan_is_the_plain_and_the_brute_force_one():
    bathy = load_bathymetry([], with_default=True)
    rng = np.random.default_rng(11)
    # shelves, banks and open ocean: the North Sea, Grand Banks, Torres Strait, the Bahamas,
    # the mid-Pacific, across the antimeridian in the Aleutians
    centres = [(3.0, 55.0), (-50.0, 45.0), (142.5, -10.0), (-77.0, 24.5), (-150.0, 10.0),
               (179.5, 52.0)]
    legs = _legs(rng, centres, 120, 4.0)
    cap = rng.uniform(12.0, 60.0, legs[0].size)  # draft + squat + waves + margin
    cap[::7] = np.inf  # exact legs ride along: the plain walk answers them
    _check(bathy, legs, cap)


def test_fine_grid_capped_scan_round_skerki_bank():
    bathy = load_bathymetry([SKERKI], with_default=False)
    rng = np.random.default_rng(12)
    legs = _legs(rng, [(11.0, 37.9)], 300, 0.7)
    _check(bathy, legs, rng.uniform(12.0, 40.0, legs[0].size))


def test_depth_levels_cover_caps_from_above():
    assert level_for(LEVELS_M[0] - 5.0) == LEVELS_M[0]
    assert all(level_for(v) == v for v in LEVELS_M)
    assert level_for(LEVELS_M[-1] + 1.0) is None and level_for(float("nan")) is None


def test_unit_vectors_are_segment_ends_bit_for_bit():
    rng = np.random.default_rng(13)
    pts = rng.uniform([-90.0, -540.0, -90.0, -540.0], [90.0, 540.0, 90.0, 540.0], (2000, 4))
    pts[:8] = [[0.0, -0.0, -0.0, 0.0], [90.0, 180.0, -90.0, -180.0], [1e-300, 0.0, 0.0, 0.0],
               [45.0, 10.0, 45.0, 10.0], [-0.0, 0.0, 0.0, -0.0], [0.0, 360.0, 0.0, 0.0],
               [60.0, 179.9, 60.0, -179.9], [-30.0, 0.0, 30.0, 180.0]]
    for la0, lo0, la1, lo1 in pts:
        want = segment_ends(la0, lo0, la1, lo1)
        a, b = dk.unit_vector(la0, lo0), dk.unit_vector(la1, lo1)
        got = (*a, *b, dk.ends_arc_deg(*a, *b))
        assert np.array_equal(np.array(got).view(np.int64), np.array(want).view(np.int64))


@pytest.mark.skipif(not default_depth_files(), reason="ETOPO5 (ferret-datasets) not installed")
def test_a_route_scans_as_its_legs_one_by_one():
    # consecutive legs share an end (the scan reuses its unit vector): each leg's depth is
    # the one it gets alone, signed zeros at a shared end included
    bathy = load_bathymetry([], with_default=True)
    rng = np.random.default_rng(14)
    starts = [(3.0, 55.0), (-50.0, 45.0), (142.5, -10.0), (-1.0, -1.0)]
    nodes = [np.cumsum(np.vstack([s, rng.normal(0.0, 1.5, (40, 2))]), axis=0) for s in starts]
    lon = np.concatenate([n[:, 0] for n in nodes] + [np.array([0.5, -0.0, 0.0, -0.5])])
    lat = np.concatenate([n[:, 1] for n in nodes] + [np.array([0.5, 0.0, -0.0, 0.5])])
    legs = (lon[:-1], lat[:-1], lon[1:], lat[1:])
    cap = np.full(lon.size - 1, 25.0)
    whole = capped_min_depth_m(bathy, *legs, cap)
    alone = np.array([capped_min_depth_m(bathy, *(e[i:i + 1] for e in legs), cap[i:i + 1])[0]
                      for i in range(cap.size)])
    assert np.array_equal(whole, alone, equal_nan=True)
    assert 0 < np.sum(whole < cap) < cap.size  # shallows and open water both met
