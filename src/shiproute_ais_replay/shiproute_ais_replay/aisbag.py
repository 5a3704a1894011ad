"""Write cleaned tracks (or any ShipState stream) into a bag: ShipState + NavSatFix per fix."""

from __future__ import annotations

import heapq
import math
from collections.abc import Iterable
from pathlib import Path
from typing import Any

import numpy as np
from rosbags.typesys.store import Typestore

from .aisclean import Track
from .bagwriter import BagWriter
from .shipstate import ShipStateRecord, to_rosbags
from .typestore import NAV_SAT_FIX_TYPE, SHIP_STATE_TYPE, build_typestore

OWN_STATE_TOPIC = "/shiproute/ship_state"
OWN_FIX_TOPIC = "/shiproute/fix"


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


def track_topics(track: Track, own: bool) -> tuple[str, str]:
    """(ShipState topic, NavSatFix topic) of a track in a bag."""
    if own:
        return OWN_STATE_TOPIC, OWN_FIX_TOPIC
    return f"/ais/mmsi_{track.mmsi}/ship_state", f"/ais/mmsi_{track.mmsi}/fix"


def write_tracks(tracks: list[Track], out: str | Path, with_fix: bool = True) -> dict[str, int]:
    """Write tracks in time order; a single track goes on the own-ship topics."""
    store = build_typestore()
    own = len(tracks) == 1
    streams = [[(rec.time_ns, i, rec) for rec in tr.states] for i, tr in enumerate(tracks)]
    with BagWriter(out, store) as writer:
        topics = [track_topics(tr, own) for tr in tracks]
        for state_topic, fix_topic in topics:
            writer.add_topic(state_topic, SHIP_STATE_TYPE)
            if with_fix:
                writer.add_topic(fix_topic, NAV_SAT_FIX_TYPE)
        for t_ns, i, rec in heapq.merge(*streams):
            writer.write_message(topics[i][0], t_ns, to_rosbags(store, rec))
            if with_fix:
                writer.write_message(topics[i][1], t_ns, navsatfix(store, rec))
        return writer.counts


def write_states(states: Iterable[ShipStateRecord], out: str | Path,
                 with_fix: bool = True) -> dict[str, int]:
    """Write a stream of own-ship states (e.g. a simulated voyage) without holding it."""
    store = build_typestore()
    with BagWriter(out, store) as writer:
        writer.add_topic(OWN_STATE_TOPIC, SHIP_STATE_TYPE)
        if with_fix:
            writer.add_topic(OWN_FIX_TOPIC, NAV_SAT_FIX_TYPE)
        for rec in states:
            writer.write_message(OWN_STATE_TOPIC, rec.time_ns, to_rosbags(store, rec))
            if with_fix:
                writer.write_message(OWN_FIX_TOPIC, rec.time_ns, navsatfix(store, rec))
        return writer.counts
