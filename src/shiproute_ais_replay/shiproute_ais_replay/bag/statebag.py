"""Write own-ship ShipState streams into a bag: ShipState + NavSatFix per state."""

from __future__ import annotations

import math
from collections.abc import Iterable
from pathlib import Path
from typing import Any

import numpy as np
from rosbags.typesys.store import Typestore
from shiproute_core.topics import OWN_FIX, SHIP_STATE

from .bagwriter import BagWriter
from .shipstate import ShipStateRecord, to_rosbags
from .typestore import NAV_SAT_FIX_TYPE, SHIP_STATE_TYPE, build_typestore


def navsatfix(store: Typestore, rec: ShipStateRecord, frame_id: str = "gps") -> Any:
    """rosbags sensor_msgs/NavSatFix of a state (GPS fix, altitude unknown)."""
    t = store.types
    header = t["std_msgs/msg/Header"](
        stamp=t["builtin_interfaces/msg/Time"](
            sec=rec.time_ns // 1_000_000_000, nanosec=rec.time_ns % 1_000_000_000),
        frame_id=frame_id,
    )
    status_cls = t["sensor_msgs/msg/NavSatStatus"]
    return t[NAV_SAT_FIX_TYPE](
        header=header,
        status=status_cls(status=0, service=1),
        latitude=rec.latitude_deg,
        longitude=rec.longitude_deg,
        altitude=math.nan,
        position_covariance=np.zeros(9),
        position_covariance_type=0,
    )


def write_states(states: Iterable[ShipStateRecord], out: str | Path,
                 with_fix: bool = True) -> dict[str, int]:
    """Write a stream of own-ship states (e.g. a simulated voyage) without holding it."""
    store = build_typestore()
    with BagWriter(out, store) as writer:
        writer.add_topic(SHIP_STATE, SHIP_STATE_TYPE)
        if with_fix:
            writer.add_topic(OWN_FIX, NAV_SAT_FIX_TYPE)
        for rec in states:
            writer.write_message(SHIP_STATE, rec.time_ns, to_rosbags(store, rec))
            if with_fix:
                writer.write_message(OWN_FIX, rec.time_ns, navsatfix(store, rec))
        return writer.counts
