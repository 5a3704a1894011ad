"""Clean AIS tracks: range checks, 'not available' codes, duplicate times and impossible jumps.

Rejected fixes are counted by reason and n/a values (kept as NaN) are counted too, so a
report shows exactly what was removed or blanked. Codes per ITU-R M.1371: lat 91 / lon 181
= no position, SOG 102.3 = n/a (102.2 = 102.2 kn or more), COG 360 = n/a, heading 511 = n/a.
"""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass

from shiproute_core.geodesy import distance_m
from shiproute_core.units import M_S_PER_KNOT

from ..bag.shipstate import ShipStateRecord
from .aistypes import NAN, AisFix, AisInput, AisStatic

MAX_SPEED_KN = 50.0
MIN_JUMP_M = 500.0  # position noise below this never counts as a jump
REANCHOR_AFTER = 3  # consecutive jump rejections after which the track restarts there


@dataclass
class Track:
    """Cleaned states of one vessel plus what was rejected/blanked while cleaning it."""

    mmsi: int
    name: str
    imo: int
    states: list[ShipStateRecord]


def _position_problem(fix: AisFix) -> str:
    lat, lon = fix.lat_deg, fix.lon_deg
    if lat == 91.0 or lon == 181.0:
        return "position_unavailable"
    if not (math.isfinite(lat) and math.isfinite(lon)) or abs(lat) > 90 or abs(lon) > 180:
        return "position_out_of_range"
    return ""


def _field(value: float, na: float, lo: float, hi: float, name: str, notes: Counter) -> float:
    """Value or NaN; counts 'name_unavailable' / 'name_out_of_range' in ``notes``."""
    if not math.isfinite(value) or value == na:
        notes[f"{name}_unavailable"] += 1
        return NAN
    if not lo <= value <= hi:
        notes[f"{name}_out_of_range"] += 1
        return NAN
    return value


def _draught_at(statics: list[AisStatic], time_ns: int) -> float:
    """Newest known draught at ``time_ns`` (the first one for fixes before any static)."""
    best = NAN
    for st in statics:
        if math.isnan(st.draught_m):
            continue
        if st.time_ns <= time_ns or math.isnan(best):
            best = st.draught_m
        if st.time_ns > time_ns:
            break
    return best


def clean_track(mmsi: int, fixes: list[AisFix], statics: list[AisStatic],
                rejected: Counter, notes: Counter, max_speed_kn: float = MAX_SPEED_KN) -> Track:
    """Sort one vessel's fixes by time and keep the plausible ones."""
    fixes = sorted(fixes, key=lambda f: f.time_ns)
    statics = sorted(statics, key=lambda s: s.time_ns)
    states: list[ShipStateRecord] = []
    last: AisFix | None = None
    jumps = 0
    for fix in fixes:
        problem = _position_problem(fix)
        if not problem and last is not None:
            if fix.time_ns == last.time_ns:
                problem = "duplicate_time"
            else:
                dist = float(distance_m(last.lon_deg, last.lat_deg, fix.lon_deg, fix.lat_deg))
                speed_kn = dist / ((fix.time_ns - last.time_ns) * 1e-9) / M_S_PER_KNOT
                if dist > MIN_JUMP_M and speed_kn > max_speed_kn:
                    jumps += 1
                    problem = "implied_speed" if jumps <= REANCHOR_AFTER else ""
                    if not problem:
                        notes["track_reanchored"] += 1
        if problem:
            rejected[problem] += 1
            continue
        jumps = 0
        last = fix
        draught = _draught_at(statics, fix.time_ns)
        states.append(ShipStateRecord(
            time_ns=fix.time_ns,
            latitude_deg=fix.lat_deg,
            longitude_deg=fix.lon_deg,
            sog_kn=_field(fix.sog_kn, 102.3, 0.0, 102.2, "sog", notes),
            cog_deg=_field(fix.cog_deg, 360.0, 0.0, 359.9, "cog", notes),
            heading_deg=_field(fix.heading_deg, 511.0, 0.0, 359.0, "heading", notes),
            draft_fore_m=draught,
            draft_aft_m=draught,
            mmsi=mmsi,
            nav_status=fix.nav_status if 0 <= fix.nav_status <= 15 else 15,
        ))
    named = [s for s in statics if s.name or s.imo]
    return Track(mmsi, named[-1].name if named else "", named[-1].imo if named else 0, states)


def clean(data: AisInput, mmsi: int | None = None,
          max_speed_kn: float = MAX_SPEED_KN) -> tuple[list[Track], Counter, Counter]:
    """Tracks (one per MMSI, or only ``mmsi``) and (rejected, notes) counters including the
    readers' rejections."""
    rejected, notes = Counter(data.rejected), Counter(data.notes)
    by_mmsi: dict[int, list[AisFix]] = {}
    for fix in data.fixes:
        if mmsi is None or fix.mmsi == mmsi:
            by_mmsi.setdefault(fix.mmsi, []).append(fix)
    tracks = []
    for key in sorted(by_mmsi):
        statics = [s for s in data.statics if s.mmsi == key]
        tracks.append(clean_track(key, by_mmsi[key], statics, rejected, notes, max_speed_kn))
    return [t for t in tracks if t.states], rejected, notes
