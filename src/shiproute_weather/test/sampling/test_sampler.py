"""ForecastSampler against a brute-force reference; wrapping, clamping, NaN and directions."""

from __future__ import annotations

import math

import numpy as np
import pytest
from shiproute_weather.contract import canonical as cv
from shiproute_weather.sampling.sampler import MIN_VALID_WEIGHT, ForecastSampler
from weather_fixtures import small_canonical


def brute(ds, name, lon, lat, t_s):
    """Loop-by-loop trilinear reference with the documented NaN and direction rules."""
    la = ds.latitude.values
    lo = ds.longitude.values
    ts = ds.time.values.astype("datetime64[ns]").astype(np.int64) / 1e9
    a = ds[name].values.astype(np.float64)
    y = (lat - la[0]) / (la[1] - la[0])
    x = ((lon - lo[0]) % 360.0) / (lo[1] - lo[0])
    if y < 0 or y > la.size - 1 or x > lo.size - 1:
        return math.nan
    t = min(max(t_s, ts[0]), ts[-1])
    it = min(int(np.searchsorted(ts, t, side="right")) - 1, ts.size - 2)
    wt = (t - ts[it]) / (ts[it + 1] - ts[it])
    iy, ix = min(int(y), la.size - 2), min(int(x), lo.size - 2)
    wy, wx = y - iy, x - ix
    direction = name in cv.DIRECTION_VARIABLES
    acc_s = acc_c = acc = wsum = 0.0
    for dt in (0, 1):
        for dy in (0, 1):
            for dx in (0, 1):
                w = (wt if dt else 1 - wt) * (wy if dy else 1 - wy) * (wx if dx else 1 - wx)
                v = a[it + dt, iy + dy, ix + dx]
                if w > 0 and not math.isnan(v):
                    wsum += w
                    acc += w * v
                    acc_s += w * math.sin(math.radians(v))
                    acc_c += w * math.cos(math.radians(v))
    if wsum < MIN_VALID_WEIGHT:
        return math.nan
    if direction:
        return math.degrees(math.atan2(acc_s / wsum, acc_c / wsum)) % 360.0
    return acc / wsum


def test_matches_brute_force_on_random_points() -> None:
    ds = small_canonical(n_time=6)
    s = ForecastSampler(ds)
    rng = np.random.default_rng(7)
    n = 400
    t0 = ds.time.values[0].astype("datetime64[ns]").astype(np.int64) / 1e9
    lon = rng.uniform(165.0, 200.0, n) - 360.0 * rng.integers(0, 2, n)  # both conventions
    lat = rng.uniform(29.0, 41.0, n)
    t = t0 + rng.uniform(-3600.0, 20 * 3600.0, n)
    got = s.sample(lon, lat, t)
    for name in cv.CANONICAL_ORDER:
        ref = np.array([brute(ds, name, *p) for p in zip(lon, lat, t, strict=True)])
        np.testing.assert_array_equal(np.isnan(got[name]), np.isnan(ref), err_msg=name)
        ok = ~np.isnan(ref)
        if name in cv.DIRECTION_VARIABLES:
            diff = (got[name][ok] - ref[ok] + 180.0) % 360.0 - 180.0
            assert np.max(np.abs(diff)) < 1e-4, name
        else:
            np.testing.assert_allclose(got[name][ok], ref[ok], rtol=1e-5, atol=1e-5,
                                       err_msg=name)


def test_antimeridian_wrap_and_shape() -> None:
    ds = small_canonical()  # longitudes 170..195 (continuous across 180)
    s = ForecastSampler(ds, [cv.WIND_U])
    t = float(ds.time.values[1].astype("datetime64[s]").astype(np.int64))
    lat = np.full((2, 3), 35.2)
    east = s.sample(np.full((2, 3), 185.3), lat, t)[cv.WIND_U]
    west = s.sample(np.full((2, 3), -174.7), lat, t)[cv.WIND_U]
    assert east.shape == (2, 3)
    np.testing.assert_allclose(east, west, rtol=0, atol=1e-9)
    # nodes are reproduced exactly, outside the regional grid is NaN
    node = s.sample(np.array([180.0]), np.array([35.0]), np.array([t]))[cv.WIND_U][0]
    assert node == pytest.approx(float(ds[cv.WIND_U].sel(latitude=35.0, longitude=180.0)[1]))
    assert np.isnan(s.sample(np.array([150.0]), np.array([35.0]), np.array([t]))[cv.WIND_U][0])
    assert np.isnan(s.sample(np.array([180.0]), np.array([50.0]), np.array([t]))[cv.WIND_U][0])


def test_global_grid_interpolates_across_the_seam() -> None:
    ds = small_canonical(lat=(-10.0, 10.0, 2.0), lon=(0.0, 358.0, 2.0))
    s = ForecastSampler(ds, [cv.WIND_V])
    t = float(ds.time.values[0].astype("datetime64[s]").astype(np.int64))
    a = ds[cv.WIND_V].values[0, 5].astype(np.float64)  # latitude 0
    got = s.sample(np.array([359.5, -0.5]), np.array([0.0, 0.0]), np.array([t, t]))[cv.WIND_V]
    expected = 0.25 * a[-1] + 0.75 * a[0]  # 359.5 is 1.5 deg past 358, 0.5 short of 360
    np.testing.assert_allclose(got, [expected, expected], rtol=1e-6)


def test_times_are_clamped_and_directions_average_as_vectors() -> None:
    ds = small_canonical(n_time=3)
    ds[cv.WAVE_DIR][:] = np.float32(350.0)
    ds[cv.WAVE_DIR][1] = np.float32(10.0)
    s = ForecastSampler(ds, [cv.WAVE_DIR, cv.WIND_U])
    ts = ds.time.values.astype("datetime64[ns]").astype(np.int64) / 1e9
    mid = 0.5 * (ts[0] + ts[1])
    got = s.sample(np.array([185.0] * 3), np.array([38.0] * 3),
                   np.array([ts[0] - 86400.0, mid, ts[-1] + 86400.0]))
    first = float(ds[cv.WIND_U].sel(latitude=38.0, longitude=185.0)[0])
    last = float(ds[cv.WIND_U].sel(latitude=38.0, longitude=185.0)[-1])
    assert got[cv.WIND_U][0] == pytest.approx(first)
    assert got[cv.WIND_U][2] == pytest.approx(last)
    assert min(got[cv.WAVE_DIR][1], 360.0 - got[cv.WAVE_DIR][1]) < 1e-4  # 350/10 -> 0, not 180


def test_large_batch_runs_fast_enough() -> None:
    import time

    ds = small_canonical(n_time=9)
    s = ForecastSampler(ds)
    rng = np.random.default_rng(0)
    n = 200_000
    args = (rng.uniform(170, 195, n), rng.uniform(30, 40, n),
            rng.uniform(0, 1, n) + float(ds.time.values[0].astype("datetime64[s]").astype(int)))
    s.sample(*args)  # compile / warm up
    t0 = time.perf_counter()
    s.sample(*args)
    assert time.perf_counter() - t0 < 2.0  # ~0.05 s on an idle core; generous under load
