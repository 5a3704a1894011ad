"""Canonical dataset -> slices / messages -> dataset is exact."""

from __future__ import annotations

from pathlib import Path

import pytest
import xarray as xr
from shiproute_weather.loaders import open_forecast
from shiproute_weather.slices import dataset_to_slices, slices_to_dataset
from weather_fixtures import small_canonical, write_nc


def test_slices_round_trip_exact(tmp_path: Path) -> None:
    ds = open_forecast([write_nc(small_canonical(n_time=4), tmp_path / "a.nc")])
    slices = list(dataset_to_slices(ds))
    assert [s.slice_index for s in slices] == [0, 1, 2, 3]
    assert slices[0].nbytes == 13 * ds.sizes["latitude"] * ds.sizes["longitude"] * 4
    xr.testing.assert_identical(slices_to_dataset(slices[::-1]), ds)


def test_messages_round_trip_exact_through_serialisation(tmp_path: Path) -> None:
    pytest.importorskip("shiproute_msgs.msg")
    from rclpy.serialization import deserialize_message, serialize_message
    from shiproute_weather.convert import dataset_to_msgs, msg_to_cycle, msgs_to_dataset
    from shiproute_weather.slices import cycle_info

    from shiproute_msgs.msg import ForecastCycle, ForecastSlice

    ds = open_forecast([write_nc(small_canonical(n_time=3), tmp_path / "b.nc")])
    cycle, msgs = dataset_to_msgs(ds, ["b.nc"])
    wire = [deserialize_message(serialize_message(m), ForecastSlice) for m in msgs]
    xr.testing.assert_identical(msgs_to_dataset(wire), ds)
    back = deserialize_message(serialize_message(cycle), ForecastCycle)
    assert msg_to_cycle(back) == cycle_info(ds, ["b.nc"])
    assert back.lon_max_deg == 195.0  # continuous across the antimeridian
