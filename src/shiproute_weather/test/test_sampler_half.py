"""Half-precision sampler storage: exact IEEE rounding, error bounds, packed construction."""

from __future__ import annotations

import numpy as np
import pytest
from shiproute_weather._half_kernel import float32_to_half_bits, interleave_half_bits
from shiproute_weather._interp_kernel import trilinear
from shiproute_weather.sampler_arrays import sampler_arrays
from shiproute_weather.sampling import ForecastSampler
from weather_fixtures import small_canonical

from shiproute_weather import canonical as cv

HALF_EPS = 2.0**-11  # binary16 rounding: |x - half(x)| <= 2^-11 |x| in the normal range


def test_half_bits_equal_numpy_float16_rounding() -> None:
    # numpy's astype(float16) is IEEE 754 round-to-nearest-even: the reference, bit for bit,
    # on random bit patterns (all exponents: NaN, inf, subnormal, overflow) and on the edges
    rng = np.random.default_rng(3)
    x = rng.integers(0, 2**32, 1_000_000, dtype=np.uint64).astype(np.uint32).view(np.float32)
    edges = np.array([0.0, -0.0, 65504.0, 65519.99, 65520.0, -65520.0, 2**-24, 2**-25,
                      3 * 2**-25, 2**-26, 2**-14, 2**-14 - 2**-25, 1.0 + 2**-11,
                      1.0 + 3 * 2**-11, np.inf, -np.inf, np.nan], dtype=np.float32)
    x = np.concatenate([x, edges, rng.normal(0, 30, 100_000).astype(np.float32)])
    got = np.empty(x.size, np.uint16)
    float32_to_half_bits(x.view(np.uint32), got)
    with np.errstate(over="ignore"):
        ref = x.astype(np.float16).view(np.uint16)
    nan = np.isnan(x)
    assert np.array_equal(got[~nan], ref[~nan])
    assert np.all(np.isnan(got[nan].view(np.float16)))


def test_interleave_writes_channel_last() -> None:
    cols = [np.arange(5, dtype=np.float32) + 10 * c for c in range(3)]
    dst = np.empty((5, 3), np.uint16)
    interleave_half_bits(tuple(c.view(np.uint32) for c in cols), dst)
    assert np.array_equal(dst.view(np.float16).astype(np.float32), np.stack(cols, axis=1))


def test_half_storage_error_is_within_the_rounding_bound() -> None:
    ds = small_canonical(n_time=6)
    full, half = ForecastSampler(ds), ForecastSampler(ds, dtype=np.float16)
    assert half.dtype == np.float16 and half.nbytes * 2 == full.nbytes
    rng = np.random.default_rng(11)
    n = 2000
    t0 = ds.time.values[0].astype("datetime64[ns]").astype(np.int64) / 1e9
    lon, lat = rng.uniform(170.0, 195.0, n), rng.uniform(30.0, 40.0, n)
    t = t0 + rng.uniform(0.0, 15 * 3600.0, n)
    a, b = full.sample(lon, lat, t), half.sample(lon, lat, t)
    for name in cv.CANONICAL_ORDER:
        assert np.array_equal(np.isnan(a[name]), np.isnan(b[name])), name
        ok = ~np.isnan(a[name])
        if name in cv.DIRECTION_VARIABLES:
            continue
        # a convex combination of nodes each rounded by <= 2^-11 of its magnitude
        bound = HALF_EPS * float(np.nanmax(np.abs(ds[name].values)))
        assert np.max(np.abs(a[name][ok] - b[name][ok])) <= bound, name
    # directions: sine and cosine each off by <= 2^-12, so where the interpolated unit vectors
    # keep a resultant r >= 0.5 the angle is off by <= sqrt(2) 2^-12 / 0.5 rad (0.04 deg)
    name = cv.WAVE_DIR
    arrays = sampler_arrays(full)
    vectors = np.empty((arrays.data.shape[3], n))
    trilinear(arrays.data, arrays.times_s, arrays.lat0_deg, arrays.dlat_deg, arrays.lon0_deg,
              arrays.dlon_deg, arrays.periodic, lon, lat, t, vectors)
    c = arrays.channels[name]
    r = np.hypot(vectors[c], vectors[c + 1])
    keep = ~np.isnan(r) & (r >= 0.5)
    assert keep.sum() > 100
    diff = np.abs((a[name][keep] - b[name][keep] + 180.0) % 360.0 - 180.0)
    assert np.max(diff) <= np.degrees(np.sqrt(2.0) * 2.0**-12 / 0.5)


def test_from_packed_wraps_the_array_and_checks_its_shape() -> None:
    ds = small_canonical(n_time=3)
    ref = ForecastSampler(ds, dtype=np.float16)
    again = ForecastSampler.from_packed(ref._data, ref.times_s, ref.grid, ref.variables)
    assert np.shares_memory(again._data, ref._data)
    lon, lat, t = np.array([180.0]), np.array([35.0]), ref.times_s[:1] + 3600.0
    assert again.sample(lon, lat, t)[cv.WIND_U] == ref.sample(lon, lat, t)[cv.WIND_U]
    with pytest.raises(ValueError, match="shape"):
        ForecastSampler.from_packed(ref._data[:, :-1], ref.times_s, ref.grid, ref.variables)
    with pytest.raises(ValueError, match="float32 or float16"):
        ForecastSampler(ds, dtype=np.float64)


def test_pack_fields_takes_read_only_buffers_next_to_computed_directions() -> None:
    # message buffers arrive read-only (bytes) while sine/cosine columns are computed arrays
    from shiproute_weather.sampling import pack_fields

    rng = np.random.default_rng(5)
    wind = rng.normal(0, 10, (4, 6)).astype(np.float32)
    wave_dir = rng.uniform(0, 360, (4, 6)).astype(np.float32)
    values = {cv.WIND_U: np.frombuffer(wind.tobytes(), dtype=np.float32).reshape(4, 6),
              cv.WAVE_DIR: wave_dir}
    names = [cv.WIND_U, cv.WAVE_DIR]
    half = np.empty((4, 6, 3), dtype=np.float16)
    full = np.empty((4, 6, 3), dtype=np.float32)
    pack_fields(half, names, values.__getitem__)
    pack_fields(full, names, values.__getitem__)
    assert np.array_equal(half, full.astype(np.float16))
