"""Helpers of the shiproute_ais_replay unit tests: small bags written by the tools."""

from __future__ import annotations

import math
from pathlib import Path

from shiproute_ais_replay.bag.bagwriter import BagWriter
from shiproute_ais_replay.bag.shipstate import ShipStateRecord, to_rosbags
from shiproute_ais_replay.bag.statebag import navsatfix
from shiproute_ais_replay.bag.typestore import NAV_SAT_FIX_TYPE, SHIP_STATE_TYPE, build_typestore
from shiproute_core.topics import OWN_FIX as OWN_FIX_TOPIC
from shiproute_core.topics import SHIP_STATE as OWN_STATE_TOPIC

DATA = Path(__file__).parent / "data"
T0_NS = 1_700_000_000_000_000_000
WGS84_A_M = 6_378_137.0  # WGS 84 semi-major axis (NIMA TR8350.2)
WGS84_F = 1 / 298.257223563  # WGS 84 flattening
EQUATOR_DEG_M = WGS84_A_M * math.pi / 180  # one degree along the equator (a geodesic) [m]


def meridian_arc_m(lat0_deg: float, lat1_deg: float) -> float:
    """Meridian arc [m] on WGS 84 from the radius of curvature M(phi) = a(1-e2)/(1-e2 sin2)^1.5
    at the mid latitude (midpoint rule: relative error < 1e-8 over arcs below one degree)."""
    e2 = WGS84_F * (2 - WGS84_F)
    mid = math.radians(0.5 * (lat0_deg + lat1_deg))
    m_radius = WGS84_A_M * (1 - e2) / (1 - e2 * math.sin(mid) ** 2) ** 1.5
    return m_radius * math.radians(lat1_deg - lat0_deg)


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
