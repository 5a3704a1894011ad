"""rosbags <-> rclpy message conversion by generic field copy, and ShipStateRecord -> rclpy."""

from __future__ import annotations

import array
import importlib
from functools import cache
from typing import Any

import numpy as np

from ..bag.shipstate import ShipStateRecord

_TYPECODES = {
    "float": "f", "double": "d", "int8": "b", "uint8": "B", "int16": "h", "uint16": "H",
    "int32": "i", "uint32": "I", "int64": "q", "uint64": "Q",
}


@cache
def rclpy_class(typename: str) -> type:
    """rclpy message class of ``pkg/msg/Name`` (or ``pkg/Name``); raises ImportError/AttributeError
    when the interface package is not installed."""
    parts = typename.split("/")
    pkg, name = parts[0], parts[-1]
    return getattr(importlib.import_module(f"{pkg}.msg"), name)


def _element_type(ftype: str) -> str:
    """'sequence<pkg/Name, 5>' -> 'pkg/Name'; 'double[9]' -> 'double'."""
    if ftype.startswith("sequence<"):
        ftype = ftype[len("sequence<") : -1].split(",")[0]
    return ftype.split("[")[0]


def _convert_value(value: Any, ftype: str) -> Any:
    elem = _element_type(ftype)
    is_seq = ftype.startswith("sequence<") or ftype.endswith("]")
    if "/" in elem:
        cls = rclpy_class(elem)
        return [to_rclpy(v, cls) for v in value] if is_seq else to_rclpy(value, cls)
    if is_seq and isinstance(value, np.ndarray):
        if ftype.startswith("sequence<") and elem in _TYPECODES:
            out = array.array(_TYPECODES[elem])
            out.frombytes(np.ascontiguousarray(value, dtype=out.typecode).tobytes())
            return out
        return value.tolist() if value.dtype.kind not in "fiu" or elem == "boolean" else value
    return value


def to_rclpy(obj: Any, cls: Any) -> Any:
    """Copy every field of a rosbags message object into a new instance of rclpy ``cls``."""
    msg = cls()
    for fname, ftype in cls.get_fields_and_field_types().items():
        setattr(msg, fname, _convert_value(getattr(obj, fname), ftype))
    return msg


def ship_state_to_rclpy(rec: ShipStateRecord, frame_id: str = "wgs84") -> Any:
    """rclpy ``shiproute_msgs/ShipState`` for a ShipStateRecord."""
    cls = rclpy_class("shiproute_msgs/msg/ShipState")
    msg = cls()
    msg.header.stamp.sec = rec.time_ns // 1_000_000_000
    msg.header.stamp.nanosec = rec.time_ns % 1_000_000_000
    msg.header.frame_id = frame_id
    msg.mmsi = int(rec.mmsi)
    msg.nav_status = int(rec.nav_status)
    for name in ("latitude_deg", "longitude_deg", "sog_kn", "cog_deg", "heading_deg", "stw_kn",
                 "shaft_rpm", "draft_fore_m", "draft_aft_m", "fuel_rate_t_per_h"):
        setattr(msg, name, float(getattr(rec, name)))
    return msg


def clock_msg(bag_ns: int) -> Any:
    """rosgraph_msgs/Clock at ``bag_ns``."""
    from rosgraph_msgs.msg import Clock

    msg = Clock()
    msg.clock.sec = bag_ns // 1_000_000_000
    msg.clock.nanosec = bag_ns % 1_000_000_000
    return msg


def diagnostic_array(stamp_ns: int, name: str, status: dict[str, Any], level: int,
                     message: str) -> Any:
    """diagnostic_msgs/DiagnosticArray with one status whose values are ``status`` items."""
    from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue

    arr = DiagnosticArray()
    arr.header.stamp.sec = stamp_ns // 1_000_000_000
    arr.header.stamp.nanosec = stamp_ns % 1_000_000_000
    st = DiagnosticStatus()
    st.level = bytes([level])
    st.name = name
    st.message = message
    st.hardware_id = "bag"
    st.values = [KeyValue(key=str(k), value=str(v)) for k, v in status.items()]
    arr.status = [st]
    return arr
