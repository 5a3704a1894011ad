"""Half-precision sampler storage: exact IEEE rounding, error bounds, packed construction."""

from __future__ import annotations

import numpy as np
import pytest
from shiproute_weather.contract import canonical as cv
from shiproute_weather.sampling.half_kernel import float32_to_half_bits
from shiproute_weather.sampling.interp_kernel import trilinear
from shiproute_weather.sampling.pack_kernel import BLOCK, F32_SCALAR, pack_half_channels
from shiproute_weather.sampling.sampler import ForecastSampler
from shiproute_weather.sampling.sampler_arrays import sampler_arrays
from weather_fixtures import small_canonical

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


def _random_float32_bits(n: int, seed: int) -> np.ndarray:
    """float32 values of random bit patterns (every exponent: NaN, inf, subnormal, overflow)."""
    rng = np.random.default_rng(seed)
    return rng.integers(0, 2**32, n, dtype=np.uint64).astype(np.uint32).view(np.float32)


@pytest.mark.parametrize("n_ch", [16, 3])  # 64-bit interleave and the 16-bit fallback
def test_pack_kernel_rounds_like_numpy_bit_for_bit(n_ch: int) -> None:
    # the kernel's float32 -> binary16 conversion (CPU instruction) on random bit patterns,
    # across block boundaries (n not a multiple of BLOCK), written channel-last
    n = 5 * BLOCK + 37
    cols = [_random_float32_bits(n, seed=c) for c in range(n_ch)]
    dst = np.empty((n, n_ch), np.uint16)
    pack_half_channels(np.array([c.ctypes.data for c in cols], dtype=np.int64),
                       np.full(n_ch, F32_SCALAR), np.zeros(n_ch), np.zeros(n_ch), dst)
    x = np.stack(cols, axis=1)
    with np.errstate(over="ignore"):
        ref = x.astype(np.float16).view(np.uint16)
    nan = np.isnan(x)
    assert np.array_equal(dst[~nan], ref[~nan])
    assert np.all(np.isnan(dst[nan].view(np.float16)))


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
    # message buffers arrive read-only (bytes) while other fields are computed arrays
    from shiproute_weather.sampling.sampler import pack_fields

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
    assert np.array_equal(half[..., 0], full[..., 0].astype(np.float16))  # scalars: exact
    assert np.all(np.abs(half[..., 1:].astype(np.float64) - full[..., 1:])
                  <= HALF_EPS * np.abs(full[..., 1:]) + 2.0**-21)


def test_directions_are_sine_and_cosine_within_half_precision() -> None:
    """The kernel's own float32 sine/cosine, rounded to half, against float64 truth (bound:
    half rounding 2^-11 |v| plus a few float32 ulps, 2^-21 |v|, plus half the smallest
    subnormal step 2^-25) and against numpy's float32 path (which also rounds the radians
    to float32: up to 3.7e-7 off at 360 deg, within 2^-21)."""
    from shiproute_weather.sampling.sampler import pack_fields

    rng = np.random.default_rng(9)
    deg = np.concatenate([rng.uniform(0, 360, 200_000), np.arange(0, 361, 0.5),
                          rng.uniform(-720, 1080, 20_000)]).astype(np.float32)
    deg[::1000] = np.nan
    half = np.empty((deg.size, 2), dtype=np.float16)
    pack_fields(half, [cv.WAVE_DIR], {cv.WAVE_DIR: deg}.__getitem__)
    got = half.astype(np.float64)
    rad = np.radians(deg.astype(np.float64))
    truth = np.stack([np.sin(rad), np.cos(rad)], axis=1)
    nan = np.isnan(deg)
    assert np.all(np.isnan(got[nan])) and not np.any(np.isnan(got[~nan]))
    err = np.abs(got[~nan] - truth[~nan])
    assert np.all(err <= (HALF_EPS + 2.0**-21) * np.abs(truth[~nan]) + 2.0**-25)
    # exact zeros and ones at multiples of 90 deg (reduction in degrees is exact)
    right = np.isin(deg, np.float32([0, 90, 180, 270, 360]))
    assert np.all(np.abs(got[right]) % 1.0 == 0.0)
    inside = ~nan & (deg >= 0) & (deg <= 360)
    rad32 = np.deg2rad(deg[inside])
    ref32 = np.stack([np.sin(rad32), np.cos(rad32)], axis=1).astype(np.float64)
    assert np.all(np.abs(got[inside] - ref32) <= HALF_EPS * np.abs(ref32) + 2.0**-21)
    # and the half-precision results differ from numpy's in a small minority only
    ref16 = ref32.astype(np.float16)
    assert np.mean(half[inside] != ref16) < 2e-3


def test_packed_codes_pack_like_their_decoded_values() -> None:
    """Wire codes go through the same kernel as float32: bit-equal to packing the decoded
    float32 values, scalars and directions, in half and in float32 storage."""
    from shiproute_weather.sampling.sampler import pack_fields
    from shiproute_weather.wire.packing import pack_field, unpack_field

    ds = small_canonical(n_time=1)
    names = list(cv.CANONICAL_ORDER)
    raw = {n: ds[n].values[0] for n in names}
    packed = {n: pack_field(v) for n, v in raw.items()}
    decoded = {n: unpack_field(p) for n, p in packed.items()}
    shape = (*raw[names[0]].shape, 16)
    mixed = {n: (packed[n] if k % 2 else decoded[n]) for k, n in enumerate(names)}
    for dtype in (np.float16, np.float32):
        a, b, c = (np.empty(shape, dtype) for _ in range(3))
        pack_fields(a, names, packed.__getitem__)
        pack_fields(b, names, decoded.__getitem__)
        pack_fields(c, names, mixed.__getitem__)
        assert np.array_equal(a.view(np.uint8), b.view(np.uint8)), dtype
        assert np.array_equal(a.view(np.uint8), c.view(np.uint8)), dtype
