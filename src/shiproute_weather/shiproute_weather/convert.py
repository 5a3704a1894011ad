"""Lossless conversion between slices/cycle info and shiproute_msgs ForecastSlice/ForecastCycle.

Field data travel as float32 sequences: numpy -> array('f') by a memory copy (no per-element
Python work), and back with numpy.frombuffer.
"""

from __future__ import annotations

import array
from collections.abc import Sequence

import numpy as np
import xarray as xr
from builtin_interfaces.msg import Time

from shiproute_msgs.msg import ForecastCycle, ForecastField, ForecastSlice

from .slices import (
    CycleInfo,
    FieldData,
    SliceData,
    SliceGrid,
    cycle_info,
    dataset_to_slices,
    slices_to_dataset,
)

FRAME_ID = "wgs84"


def ns_to_time(ns: int) -> Time:
    """builtin_interfaces/Time from nanoseconds since the epoch."""
    return Time(sec=int(ns // 1_000_000_000), nanosec=int(ns % 1_000_000_000))


def time_to_ns(t: Time) -> int:
    """Nanoseconds since the epoch of a builtin_interfaces/Time."""
    return int(t.sec) * 1_000_000_000 + int(t.nanosec)


def _f32(values: np.ndarray) -> array.array:
    a = array.array("f")
    a.frombytes(memoryview(np.ascontiguousarray(values, dtype=np.float32)).cast("B"))
    return a


def slice_to_msg(s: SliceData, stamp: Time | None = None) -> ForecastSlice:
    """ForecastSlice message of a slice."""
    msg = ForecastSlice()
    msg.header.frame_id = FRAME_ID
    if stamp is not None:
        msg.header.stamp = stamp
    msg.cycle_id = s.cycle_id
    msg.reference_time = ns_to_time(s.reference_time_ns)
    msg.valid_time = ns_to_time(s.valid_time_ns)
    msg.slice_index = s.slice_index
    msg.slice_count = s.slice_count
    msg.source = s.source
    g = s.grid
    msg.lat0_deg, msg.lon0_deg = g.lat0_deg, g.lon0_deg
    msg.dlat_deg, msg.dlon_deg = g.dlat_deg, g.dlon_deg
    msg.n_lat, msg.n_lon = g.n_lat, g.n_lon
    fields = []
    for f in s.fields:
        fm = ForecastField()
        fm.name, fm.units, fm.direction_convention = f.name, f.units, f.direction_convention
        fm.data = _f32(f.data)
        fields.append(fm)
    msg.fields = fields
    return msg


def msg_to_slice(msg: ForecastSlice) -> SliceData:
    """Slice of a ForecastSlice message (field arrays are float32 copies)."""
    return _slice_of(msg, copy=True)


def _slice_of(msg: ForecastSlice, copy: bool) -> SliceData:
    """Slice of a message; with copy=False the arrays are views on the message's buffers."""
    grid = SliceGrid(float(msg.lat0_deg), float(msg.lon0_deg), float(msg.dlat_deg),
                     float(msg.dlon_deg), int(msg.n_lat), int(msg.n_lon))
    fields = tuple(FieldData(f.name, f.units, f.direction_convention,
                             _f32_array(f.data, copy))
                   for f in msg.fields)
    return SliceData(msg.cycle_id, time_to_ns(msg.reference_time), time_to_ns(msg.valid_time),
                     int(msg.slice_index), int(msg.slice_count), msg.source, grid, fields)


def _f32_array(data: array.array, copy: bool) -> np.ndarray:
    view = np.frombuffer(data, dtype=np.float32)
    return view.copy() if copy else view


def cycle_to_msg(c: CycleInfo, stamp: Time | None = None) -> ForecastCycle:
    """ForecastCycle message of a cycle announcement."""
    msg = ForecastCycle()
    msg.header.frame_id = FRAME_ID
    if stamp is not None:
        msg.header.stamp = stamp
    msg.cycle_id = c.cycle_id
    msg.reference_time = ns_to_time(c.reference_time_ns)
    msg.first_valid_time = ns_to_time(c.first_valid_time_ns)
    msg.last_valid_time = ns_to_time(c.last_valid_time_ns)
    msg.step_s = c.step_s
    msg.slice_count = c.slice_count
    msg.source = c.source
    msg.lat_min_deg, msg.lat_max_deg = c.lat_min_deg, c.lat_max_deg
    msg.lon_min_deg, msg.lon_max_deg = c.lon_min_deg, c.lon_max_deg
    msg.fields = list(c.fields)
    msg.source_files = list(c.source_files)
    return msg


def msg_to_cycle(msg: ForecastCycle) -> CycleInfo:
    """Cycle announcement of a ForecastCycle message."""
    return CycleInfo(msg.cycle_id, time_to_ns(msg.reference_time),
                     time_to_ns(msg.first_valid_time), time_to_ns(msg.last_valid_time),
                     float(msg.step_s), int(msg.slice_count), msg.source,
                     float(msg.lat_min_deg), float(msg.lat_max_deg), float(msg.lon_min_deg),
                     float(msg.lon_max_deg), tuple(msg.fields), tuple(msg.source_files))


def dataset_to_msgs(ds: xr.Dataset, source_files: Sequence[str] = ()
                    ) -> tuple[ForecastCycle, list[ForecastSlice]]:
    """The cycle announcement and all slice messages of a canonical dataset."""
    return (cycle_to_msg(cycle_info(ds, source_files)),
            [slice_to_msg(s) for s in dataset_to_slices(ds)])


def msgs_to_dataset(slices: Sequence[ForecastSlice]) -> xr.Dataset:
    """Canonical dataset from the complete set of a cycle's ForecastSlice messages.

    The messages' buffers are read in place (no per-slice copy): the dataset is one copy.
    """
    return slices_to_dataset([_slice_of(m, copy=False) for m in slices])
