"""Canonical dataset -> slices / messages -> dataset: exact in float32, within the packing
bound in 16-bit packing."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from shiproute_weather.contract.record import without_record
from shiproute_weather.ingest.loaders import open_forecast
from shiproute_weather.wire.slices import dataset_to_slices, slices_to_dataset
from weather_fixtures import small_canonical, write_nc


def test_slices_round_trip_exact(tmp_path: Path) -> None:
    ds = without_record(open_forecast([write_nc(small_canonical(n_time=4), tmp_path / "a.nc")]))
    slices = list(dataset_to_slices(ds))
    assert [s.slice_index for s in slices] == [0, 1, 2, 3]
    assert slices[0].nbytes == 13 * ds.sizes["latitude"] * ds.sizes["longitude"] * 4
    xr.testing.assert_identical(slices_to_dataset(slices[::-1]), ds)


def test_messages_round_trip_exact_through_serialisation(tmp_path: Path) -> None:
    pytest.importorskip("shiproute_msgs.msg")
    from rclpy.serialization import deserialize_message, serialize_message
    from shiproute_weather.ros.convert import dataset_to_msgs, msg_to_cycle, msgs_to_dataset
    from shiproute_weather.wire.slices import cycle_info

    from shiproute_msgs.msg import ForecastCycle, ForecastSlice

    ds = without_record(open_forecast([write_nc(small_canonical(n_time=3), tmp_path / "b.nc")]))
    cycle, msgs = dataset_to_msgs(ds, ["b.nc"], encoding="float32")
    wire = [deserialize_message(serialize_message(m), ForecastSlice) for m in msgs]
    assert all(len(f.packed) == 0 for m in wire for f in m.fields)
    xr.testing.assert_identical(msgs_to_dataset(wire), ds)
    back = deserialize_message(serialize_message(cycle), ForecastCycle)
    assert msg_to_cycle(back) == cycle_info(ds, ["b.nc"])
    assert back.lon_max_deg == 195.0  # continuous across the antimeridian


def test_packed_messages_round_trip_within_the_packing_bound(tmp_path: Path) -> None:
    """Default encoding: 16-bit codes on the wire (half the serialised bytes); the decoded
    dataset has the same grid, times, attrs and NaN pattern, values within scale / 2 of the
    originals plus one float32 rounding, and msg_to_slice decodes the same values."""
    pytest.importorskip("shiproute_msgs.msg")
    from rclpy.serialization import deserialize_message, serialize_message
    from shiproute_weather.ros.convert import (
        dataset_to_msgs,
        msg_to_slice,
        msgs_to_dataset,
        wire_bytes,
    )

    from shiproute_msgs.msg import ForecastSlice

    ds = without_record(open_forecast([write_nc(small_canonical(n_time=3), tmp_path / "c.nc")]))
    _, msgs = dataset_to_msgs(ds)
    _, exact = dataset_to_msgs(ds, encoding="float32")
    n = ds.sizes["latitude"] * ds.sizes["longitude"]
    assert wire_bytes(msgs[0]) == 13 * n * 2 and wire_bytes(exact[0]) == 13 * n * 4
    # serialised: the values take half the bytes; the rest (header, names, sequence lengths,
    # the scale constants every field carries) differs only by alignment padding (< 8 B each)
    rest_packed = len(serialize_message(msgs[0])) - 13 * n * 2
    rest_exact = len(serialize_message(exact[0])) - 13 * n * 4
    assert abs(rest_packed - rest_exact) < 13 * 8
    wire = [deserialize_message(serialize_message(m), ForecastSlice) for m in msgs]
    back = msgs_to_dataset(wire)
    assert back.attrs == ds.attrs and back.sizes == ds.sizes
    for c in ("time", "latitude", "longitude"):
        assert np.array_equal(back[c].values, ds[c].values)
    for k, m in enumerate(wire):
        s = msg_to_slice(m)
        for f, fm in zip(s.fields, m.fields, strict=True):
            assert len(fm.data) == 0 and len(fm.packed) == n
            orig = ds[f.name].values[k].reshape(-1).astype(np.float64)
            got = back[f.name].values[k].reshape(-1)
            assert np.array_equal(got, f.data, equal_nan=True)
            assert np.array_equal(np.isnan(got), np.isnan(orig))
            ok = ~np.isnan(orig)
            bound = fm.scale_factor / 2 * (1 + 1e-9) + np.spacing(
                np.abs(orig[ok]).astype(np.float32)).astype(np.float64)
            assert np.all(np.abs(got[ok] - orig[ok]) <= bound), f.name
            assert fm.add_offset == np.nanmin(orig)
            assert fm.scale_factor == pytest.approx((np.nanmax(orig) - np.nanmin(orig)) / 65534,
                                                    rel=1e-12)
