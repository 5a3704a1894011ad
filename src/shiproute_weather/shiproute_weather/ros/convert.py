"""Conversion between slices/cycle info and shiproute_msgs ForecastSlice/ForecastCycle.

Field data travel in one of two encodings (see ForecastField.msg): "packed16", 16-bit simple
packing (`wire_packing`: half the bytes, decoded values within scale_factor / 2 of the
originals), the default on the wire; or "float32", exact. Arrays go numpy -> array.array by a
memory copy (no per-element Python work) and come back with numpy.frombuffer; a field holding
+-inf is sent as float32 whatever the encoding (no 16-bit code represents it).
"""

from __future__ import annotations

import array
from collections.abc import Sequence

import numpy as np
import xarray as xr
from builtin_interfaces.msg import Time

from shiproute_msgs.msg import ForecastCycle, ForecastField, ForecastSlice

from ..errors import PackingError
from ..wire.packing import PackedField, field_values, pack_field, unpack_field
from ..wire.slices import (
    CycleInfo,
    FieldData,
    SliceData,
    SliceGrid,
    cycle_info,
    dataset_to_slices,
    slices_to_dataset,
)

FRAME_ID = "wgs84"
#: field encodings of a ForecastSlice: 16-bit simple packing, or exact float32
SLICE_ENCODINGS = ("packed16", "float32")
DEFAULT_SLICE_ENCODING = "packed16"


def ns_to_time(ns: int) -> Time:
    """builtin_interfaces/Time from nanoseconds since the epoch."""
    return Time(sec=int(ns // 1_000_000_000), nanosec=int(ns % 1_000_000_000))


def time_to_ns(t: Time) -> int:
    """Nanoseconds since the epoch of a builtin_interfaces/Time."""
    return int(t.sec) * 1_000_000_000 + int(t.nanosec)


def _array(typecode: str, values: np.ndarray) -> array.array:
    a = array.array(typecode)
    a.frombytes(np.ascontiguousarray(values).data.cast("B"))
    return a


def check_encoding(encoding: str) -> str | None:
    """Reason why `encoding` is not a slice encoding, or None when it is."""
    if encoding not in SLICE_ENCODINGS:
        return f"slice_encoding must be one of {', '.join(SLICE_ENCODINGS)}, got {encoding!r}"
    return None


def field_to_msg(f: FieldData, encoding: str = DEFAULT_SLICE_ENCODING) -> ForecastField:
    """ForecastField of one field: packed (unless it holds +-inf) or float32."""
    fm = ForecastField()
    fm.name, fm.units, fm.direction_convention = f.name, f.units, f.direction_convention
    values, packed = f.data, None
    if encoding == "float32" and isinstance(values, PackedField):
        values = unpack_field(values)
    elif isinstance(values, PackedField):
        packed = values
    elif encoding == "packed16":
        try:
            packed = pack_field(values, f.name)
        except PackingError:
            packed = None
    if packed is None:
        fm.data = _array("f", np.asarray(values, dtype=np.float32))
    else:
        fm.packed = _array("H", packed.codes)
        fm.add_offset, fm.scale_factor = float(packed.add_offset), float(packed.scale_factor)
    return fm


def slice_to_msg(s: SliceData, stamp: Time | None = None,
                 encoding: str = DEFAULT_SLICE_ENCODING) -> ForecastSlice:
    """ForecastSlice message of a slice, fields in `encoding` ("packed16" or "float32")."""
    reason = check_encoding(encoding)
    if reason is not None:
        raise ValueError(reason)
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
    msg.fields = [field_to_msg(f, encoding) for f in s.fields]
    msg.member, msg.member_count, msg.member_label = s.member, s.member_count, s.member_label
    return msg


def wire_bytes(msg: ForecastSlice) -> int:
    """Bytes of field values a slice message carries (float32 data and packed codes)."""
    return sum(4 * len(f.data) + 2 * len(f.packed) for f in msg.fields)


def msg_to_slice(msg: ForecastSlice) -> SliceData:
    """Slice of a ForecastSlice message (field arrays are float32 copies, packed fields
    decoded)."""
    return _slice_of(msg, copy=True)


def _slice_of(msg: ForecastSlice, copy: bool) -> SliceData:
    """Slice of a message; with copy=False the arrays are views on the message's buffers
    (packed fields stay packed: `slices_to_dataset` decodes them in place)."""
    grid = SliceGrid(float(msg.lat0_deg), float(msg.lon0_deg), float(msg.dlat_deg),
                     float(msg.dlon_deg), int(msg.n_lat), int(msg.n_lon))
    fields = []
    for f in msg.fields:
        values = field_values(f)
        if copy:
            values = (unpack_field(values) if isinstance(values, PackedField)
                      else values.copy())
        fields.append(FieldData(f.name, f.units, f.direction_convention, values))
    return SliceData(msg.cycle_id, time_to_ns(msg.reference_time), time_to_ns(msg.valid_time),
                     int(msg.slice_index), int(msg.slice_count), msg.source, grid,
                     tuple(fields), int(msg.member), max(1, int(msg.member_count)),
                     str(msg.member_label))


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
    msg.field_sources = list(c.field_sources)
    msg.notes = list(c.notes)
    msg.member_count = c.member_count
    msg.member_labels = list(c.member_labels)
    msg.member_kind = c.member_kind
    return msg


def msg_to_cycle(msg: ForecastCycle) -> CycleInfo:
    """Cycle announcement of a ForecastCycle message."""
    return CycleInfo(msg.cycle_id, time_to_ns(msg.reference_time),
                     time_to_ns(msg.first_valid_time), time_to_ns(msg.last_valid_time),
                     float(msg.step_s), int(msg.slice_count), msg.source,
                     float(msg.lat_min_deg), float(msg.lat_max_deg), float(msg.lon_min_deg),
                     float(msg.lon_max_deg), tuple(msg.fields), tuple(msg.source_files),
                     tuple(msg.field_sources), tuple(msg.notes),
                     max(1, int(msg.member_count)),  # 0: a publisher from before members
                     tuple(msg.member_labels), str(msg.member_kind))


def dataset_to_msgs(ds: xr.Dataset, source_files: Sequence[str] = (),
                    encoding: str = DEFAULT_SLICE_ENCODING
                    ) -> tuple[ForecastCycle, list[ForecastSlice]]:
    """The cycle announcement and all slice messages of a canonical dataset."""
    return (cycle_to_msg(cycle_info(ds, source_files)),
            [slice_to_msg(s, encoding=encoding) for s in dataset_to_slices(ds)])


def msgs_to_dataset(slices: Sequence[ForecastSlice], member_kind: str = "ensemble"
                    ) -> xr.Dataset:
    """Canonical dataset from the complete set of a cycle's ForecastSlice messages (with a
    member dimension for several members; `member_kind` from the cycle's announcement).

    The messages' buffers are read in place (no per-slice copy; packed fields are decoded
    straight into the dataset's arrays): the dataset is one copy.
    """
    return slices_to_dataset([_slice_of(m, copy=False) for m in slices], member_kind)
