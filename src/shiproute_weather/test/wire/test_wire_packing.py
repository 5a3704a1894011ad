"""16-bit simple packing of forecast fields for the wire: error bound, edge cases, messages."""

from __future__ import annotations

import numpy as np
import pytest
from shiproute_weather.errors import PackingError
from shiproute_weather.wire.packing import (
    MAX_CODE,
    MISSING_CODE,
    PackedField,
    pack_field,
    unpack_field,
)


def _bound(p: PackedField, x: np.ndarray) -> np.ndarray:
    """The documented bound: scale / 2 (float64 arithmetic adds ~1e-16 relative) plus one
    float32 rounding of the decoded value, half its float32 spacing."""
    mag = np.abs(x.astype(np.float64)) + p.scale_factor
    return p.scale_factor / 2 * (1 + 1e-9) + np.spacing(mag.astype(np.float32)) / 2


@pytest.mark.parametrize("offset, spread", [(0.0, 1.0), (-40.0, 30.0), (1e6, 0.5),
                                            (0.0, 1e-30), (0.0, 3e38), (180.0, 180.0)])
def test_decoding_error_is_within_half_a_step(offset: float, spread: float) -> None:
    rng = np.random.default_rng(7)
    x = (offset + spread * rng.uniform(-1, 1, 50_000)).astype(np.float32)
    x[rng.random(x.size) < 0.1] = np.nan  # land
    p = pack_field(x)
    finite = ~np.isnan(x)
    lo, hi = float(np.min(x[finite])), float(np.max(x[finite]))
    assert p.add_offset == lo and p.scale_factor == (hi - lo) / MAX_CODE
    assert p.codes.dtype == np.uint16 and p.codes.size == x.size
    assert np.array_equal(p.codes == MISSING_CODE, ~finite)  # 65535 only where missing
    y = unpack_field(p)
    assert y.dtype == np.float32 and np.array_equal(np.isnan(y), ~finite)
    err = np.abs(y[finite].astype(np.float64) - x[finite])
    assert np.all(err <= _bound(p, x[finite]))
    # rounded to nearest, not truncated: with 45,000 values some land near half a step
    if p.scale_factor > 1e-6 * max(abs(lo), abs(hi)):
        assert err.max() > 0.45 * p.scale_factor
    # the ends of the range decode exactly
    assert y[np.argmin(np.where(finite, x, np.inf))] == lo
    assert y[np.argmax(np.where(finite, x, -np.inf))] == hi


def test_constant_field_is_exact() -> None:
    x = np.full(1000, 3.25, dtype=np.float32)
    x[::9] = np.nan
    p = pack_field(x)
    assert (p.add_offset, p.scale_factor) == (3.25, 0.0)
    assert np.all(p.codes[~np.isnan(x)] == 0)
    assert np.array_equal(unpack_field(p), x, equal_nan=True)


def test_all_missing_field() -> None:
    p = pack_field(np.full((4, 5), np.nan, dtype=np.float32))
    assert (p.add_offset, p.scale_factor) == (0.0, 0.0)
    assert np.all(p.codes == MISSING_CODE) and p.codes.shape == (20,)
    assert np.all(np.isnan(unpack_field(p)))


@pytest.mark.parametrize("bad", [np.inf, -np.inf])
def test_infinity_is_rejected_with_the_field_name(bad: float) -> None:
    x = np.arange(10, dtype=np.float32)
    x[4] = bad
    with pytest.raises(PackingError, match=r"wind_speed.*inf"):
        pack_field(x, "wind_speed")
    x[:] = np.nan
    x[2] = bad  # alone among NaNs: still infinite, not "all missing"
    with pytest.raises(PackingError):
        pack_field(x)


def test_unpack_checks_the_output_array() -> None:
    x = np.array([0.0, 1.0, 32767.0, 65534.0], dtype=np.float32)  # scale 1: exact codes
    p = pack_field(x)
    assert p.scale_factor == 1.0 and np.array_equal(p.codes, x)
    with pytest.raises(ValueError, match="does not fit"):
        unpack_field(p, out=np.empty(3, dtype=np.float32))
    out = np.empty(4, dtype=np.float32)
    assert unpack_field(p, out=out) is out and np.array_equal(out, x)


def test_messages_carry_exactly_one_encoding_per_field() -> None:
    pytest.importorskip("shiproute_msgs.msg")
    from shiproute_weather.errors import SliceError
    from shiproute_weather.ros.convert import (
        check_encoding,
        field_values,
        msg_to_slice,
        slice_to_msg,
    )
    from shiproute_weather.wire.slices import FieldData, SliceData, SliceGrid

    rng = np.random.default_rng(3)
    wind = rng.normal(5, 6, 12).astype(np.float32)
    odd = wind.copy()
    odd[3] = np.inf  # cannot be packed: travels as float32
    s = SliceData("c", 0, 0, 0, 1, "test", SliceGrid(0.0, 0.0, 1.0, 1.0, 3, 4),
                  (FieldData("eastward_wind", "m s-1", "", wind),
                   FieldData("northward_wind", "m s-1", "", odd)))
    packed = slice_to_msg(s)
    assert len(packed.fields[0].packed) == 12 and len(packed.fields[0].data) == 0
    assert len(packed.fields[1].data) == 12 and len(packed.fields[1].packed) == 0
    back = msg_to_slice(packed)
    p = pack_field(wind)
    assert np.array_equal(back.fields[0].data, unpack_field(p))
    assert np.array_equal(back.fields[1].data, odd)  # inf kept exactly
    exact = slice_to_msg(s, encoding="float32")
    assert all(len(f.packed) == 0 for f in exact.fields)
    assert np.array_equal(msg_to_slice(exact).fields[0].data, wind)
    # a decoded slice re-sent as float32 carries the decoded values
    again = slice_to_msg(back, encoding="float32")
    assert np.array_equal(np.frombuffer(again.fields[0].data, np.float32), unpack_field(p))
    assert check_encoding("packed16") is None and check_encoding("float32") is None
    assert "packed16, float32" in str(check_encoding("float16"))
    with pytest.raises(ValueError, match="slice_encoding must be one of"):
        slice_to_msg(s, encoding="float16")
    broken = slice_to_msg(s)
    broken.fields[0].data = wind.tolist()  # both encodings set
    with pytest.raises(SliceError, match="both data"):
        field_values(broken.fields[0])
