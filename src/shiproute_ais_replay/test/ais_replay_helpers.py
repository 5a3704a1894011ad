"""Helpers of the shiproute_ais_replay unit tests: small bags written by the tools."""

from __future__ import annotations

from pathlib import Path

from shiproute_ais_replay.aisbag import OWN_FIX_TOPIC, OWN_STATE_TOPIC, navsatfix
from shiproute_ais_replay.bagwriter import BagWriter
from shiproute_ais_replay.shipstate import ShipStateRecord, to_rosbags
from shiproute_ais_replay.typestore import NAV_SAT_FIX_TYPE, SHIP_STATE_TYPE, build_typestore

DATA = Path(__file__).parent / "data"
T0_NS = 1_700_000_000_000_000_000


def make_states(n: int, dt_s: float = 1.0) -> list[ShipStateRecord]:
    """A ship steaming north at 0.001 deg per step with distinct values in every field."""
    return [
        ShipStateRecord(
            time_ns=T0_NS + int(i * dt_s * 1e9), latitude_deg=30.0 + 0.001 * i,
            longitude_deg=140.0 - 0.0005 * i, sog_kn=12.0 + 0.01 * (i % 7),
            cog_deg=1.5, heading_deg=2.5, stw_kn=11.5, shaft_rpm=70.0 + 0.1 * (i % 3),
            draft_fore_m=11.0, draft_aft_m=12.0, fuel_rate_t_per_h=1.8, mmsi=211001234,
            nav_status=0,
        )
        for i in range(n)
    ]


def write_bag(path: Path, states: list[ShipStateRecord], chunk_bytes: int = 1 << 20,
              with_fix: bool = True) -> Path:
    """Bag with ShipState (+ NavSatFix) of ``states``."""
    store = build_typestore()
    with BagWriter(path, store, chunk_bytes=chunk_bytes) as w:
        w.add_topic(OWN_STATE_TOPIC, SHIP_STATE_TYPE)
        if with_fix:
            w.add_topic(OWN_FIX_TOPIC, NAV_SAT_FIX_TYPE)
        for rec in states:
            w.write_message(OWN_STATE_TOPIC, rec.time_ns, to_rosbags(store, rec))
            if with_fix:
                w.write_message(OWN_FIX_TOPIC, rec.time_ns, navsatfix(store, rec))
    return path
