"""The weather node's slice spool: slices come back byte-exact (but for the stamp), in order,
their stamp rewritten where CDR puts it; a bad buffer or a short file is a SpoolError."""

from __future__ import annotations

import array
import os
from pathlib import Path

import pytest

pytest.importorskip("rclpy")
pytest.importorskip("shiproute_msgs.msg")

from rclpy.serialization import deserialize_message, serialize_message
from shiproute_weather.errors import SpoolError
from shiproute_weather.ros.spool import SliceSpool, restamped, spool_slice

from shiproute_msgs.msg import ForecastField, ForecastSlice


def _slice(k: int) -> ForecastSlice:
    m = ForecastSlice(cycle_id="c-1", slice_index=k, slice_count=3, n_lat=2, n_lon=3,
                      lat0_deg=-10.0, dlat_deg=0.5, lon0_deg=179.5, dlon_deg=0.25)
    m.header.frame_id = "wgs84"
    m.header.stamp.sec, m.header.stamp.nanosec = 17, 5
    m.valid_time.sec = 1772560800 + 3600 * k
    m.fields = [ForecastField(name="eastward_wind", units="m s-1",
                              packed=array.array("H", [0, 1, 65534, 65535, k, 7]),
                              add_offset=-3.0, scale_factor=0.01),
                ForecastField(name="sea_surface_wave_significant_height", units="m",
                              data=array.array("f", [float("nan"), -0.0, 1e38, 2.5, k, 0.0]))]
    return m


def test_slices_come_back_in_order_with_the_new_stamp(tmp_path: Path) -> None:
    spool = SliceSpool(str(tmp_path))
    try:
        sizes = [spool_slice(spool, _slice(k), "sess-3") for k in range(3)]
        assert sizes == [2 * 6 + 4 * 6] * 3  # bytes of field values: 6 codes + 6 floats
        assert len(spool) == 3
        assert os.listdir(tmp_path) == []  # unlinked: nothing left behind, even on a kill -9
        for k in range(3):
            back = deserialize_message(spool.serialized(k, 1772560800, 999_999_999),
                                       ForecastSlice)
            want = _slice(k)
            want.publication_id = "sess-3"
            want.header.stamp.sec, want.header.stamp.nanosec = 1772560800, 999_999_999
            assert serialize_message(back) == serialize_message(want)
    finally:
        spool.close()


def test_restamp_handles_both_byte_orders_and_refuses_other_bytes() -> None:
    data = serialize_message(_slice(0))
    big = b"\x00\x00" + data[2:4] + b"\x00" * 8
    assert restamped(big, 1, 2)[4:12] == (1).to_bytes(4, "big") + (2).to_bytes(4, "big")
    little = restamped(data, -1, 2)
    assert little[4:12] == (-1).to_bytes(4, "little", signed=True) + (2).to_bytes(4, "little")
    assert little[12:] == data[12:]
    with pytest.raises(SpoolError, match="not a CDR"):
        restamped(b"\x07\x01\x00\x00" + b"\x00" * 8, 1, 2)
    with pytest.raises(SpoolError, match="not a CDR"):
        restamped(b"\x00\x01\x00", 1, 2)


def test_a_short_file_is_a_spool_error(tmp_path: Path) -> None:
    spool = SliceSpool(str(tmp_path))
    try:
        spool.append(_slice(0))
        os.ftruncate(spool._file.fileno(), 10)  # the disk lost the slice
        with pytest.raises(SpoolError, match="slice 0"):
            spool.serialized(0, 0, 0)
    finally:
        spool.close()


def test_a_missing_directory_is_a_spool_error(tmp_path: Path) -> None:
    with pytest.raises(SpoolError, match="no slice spool file"):
        SliceSpool(str(tmp_path / "absent"))
