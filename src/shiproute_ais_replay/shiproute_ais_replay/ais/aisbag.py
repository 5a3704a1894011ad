"""Write cleaned AIS tracks into a bag: ShipState + NavSatFix per fix, one topic pair a ship."""

from __future__ import annotations

import heapq
from pathlib import Path

from shiproute_core.topics import OWN_FIX, SHIP_STATE

from ..bag.bagwriter import BagWriter
from ..bag.shipstate import to_rosbags
from ..bag.statebag import navsatfix
from ..bag.typestore import NAV_SAT_FIX_TYPE, SHIP_STATE_TYPE, build_typestore
from .aisclean import Track


def track_topics(track: Track, own: bool) -> tuple[str, str]:
    """(ShipState topic, NavSatFix topic) of a track in a bag."""
    if own:
        return SHIP_STATE, OWN_FIX
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
