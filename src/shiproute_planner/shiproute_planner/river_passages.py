"""River and channel passages of ports up a river: the time the schedule gives them.

A port up a river or channel narrower than the coastline data (`geo.port_aliases.RIVER_PORTS`:
Houston, Hamburg, Antwerp, Montreal, ...) is planned from and to the channel's seaward end
(the pilot boarding area). The river passage between that end and the berth is pilotage and
not planned, but it takes time: the voyage's departure from the seaward end is the berth's
departure plus the river passage, and the seaward end must be reached the river passage
before the RTA at the berth. The passage's length is the sea lane's (`searoute`, which
follows the river) between the seaward end and the gazetteer's berth; it is sailed at
`RIVER_TRANSIT_KN` (10 kn: Les Escoumins - Montreal, ~230 NM in ~23 h; Vlissingen - Antwerp,
Cuxhaven - Hamburg and Bolivar Roads - Houston at 10-12 kn; tide and lock waiting not
included). The plan states each river passage, its time and the berth times.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from datetime import UTC, datetime

from shiproute_core.units import M_PER_NM

from .geo.ports import Port

RIVER_TRANSIT_KN = 10.0


@dataclass(frozen=True)
class RiverPassage:
    """A port's river passage: its length along the sea lane and its time at the transit
    speed."""

    port: str
    channel_end_lat_deg: float
    channel_end_lon_deg: float
    length_nm: float
    hours: float

    @property
    def seconds(self) -> float:
        """Transit time [s]."""
        return self.hours * 3600.0


def river_passage(port: Port) -> RiverPassage | None:
    """The river passage of a port planned from its channel's seaward end (None for a port
    at sea)."""
    if port.berth_lat_deg is None or port.berth_lon_deg is None:
        return None
    from .voyage.legs import sea_distance_m

    length_m = sea_distance_m(round(port.lon_deg, 4), round(port.lat_deg, 4),
                              round(port.berth_lon_deg, 4), round(port.berth_lat_deg, 4))
    length_nm = length_m / M_PER_NM
    return RiverPassage(port.name, port.lat_deg, port.lon_deg, length_nm,
                        length_nm / RIVER_TRANSIT_KN)


def _iso(t_s: float) -> str:
    return datetime.fromtimestamp(t_s, UTC).strftime("%Y-%m-%dT%H:%MZ")


def river_times(origin: Port, destination: Port, depart_s: float, rta_s: float
                ) -> tuple[float, float, list[str], list[dict]]:
    """(departure from the origin's seaward end, RTA at the destination's seaward end, notes
    for the plan, rows for the plan's `extra["river_passages"]`): the river passages' times
    taken off the voyage's time at both ends."""
    notes: list[str] = []
    rows: list[dict] = []
    dep = river_passage(origin)
    if dep is not None:
        start = depart_s + dep.seconds
        notes.append(
            f"departure from {origin.name}: the river passage from the berth to the channel's "
            f"seaward end ({dep.channel_end_lat_deg:.2f}, {dep.channel_end_lon_deg:.2f}), "
            f"{dep.length_nm:.0f} NM along the sea lane at {RIVER_TRANSIT_KN:g} kn, takes "
            f"{dep.hours:.1f} h (pilotage, not planned): the planned passage leaves the "
            f"seaward end at {_iso(start)}")
        rows.append({"port": origin.name, "end": "departure", "length_nm": dep.length_nm,
                     "speed_kn": RIVER_TRANSIT_KN, "hours": dep.hours,
                     "berth_s": depart_s, "channel_end_s": start,
                     "channel_end": [dep.channel_end_lat_deg, dep.channel_end_lon_deg]})
        depart_s = start
    arr = river_passage(destination)
    if arr is not None and math.isfinite(rta_s):
        by = rta_s - arr.seconds
        notes.append(
            f"arrival at {destination.name}: the river passage from the channel's seaward end "
            f"({arr.channel_end_lat_deg:.2f}, {arr.channel_end_lon_deg:.2f}) to the berth, "
            f"{arr.length_nm:.0f} NM along the sea lane at {RIVER_TRANSIT_KN:g} kn, takes "
            f"{arr.hours:.1f} h (pilotage, not planned): the planned passage must reach the "
            f"seaward end by {_iso(by)} for the berth RTA {_iso(rta_s)}")
        rows.append({"port": destination.name, "end": "arrival", "length_nm": arr.length_nm,
                     "speed_kn": RIVER_TRANSIT_KN, "hours": arr.hours,
                     "berth_s": rta_s, "channel_end_s": by,
                     "channel_end": [arr.channel_end_lat_deg, arr.channel_end_lon_deg]})
        rta_s = by
    return depart_s, rta_s, notes, rows


def river_calls(vias: list[Port], calls: list) -> tuple[list, list[str], list[dict]]:
    """Port calls of intermediate river ports with their river passages in and out: the
    window moves earlier by the passage in (it is the berth's), and the berth time grows by
    both passages (the ship is away from the seaward end that long)."""
    import dataclasses

    from .voyage.port_calls import PortCall

    out, notes, rows = list(calls), [], []
    for k, port in enumerate(vias):
        rp = river_passage(port)
        if rp is None or k >= len(out):
            continue
        call = out[k] if out[k] is not None else PortCall(port.name)
        out[k] = dataclasses.replace(
            call, earliest_s=None if call.earliest_s is None else call.earliest_s - rp.seconds,
            latest_s=None if call.latest_s is None else call.latest_s - rp.seconds,
            berth_s=call.berth_s + 2.0 * rp.seconds)
        notes.append(f"call at {port.name}: the river passage between the channel's seaward "
                     f"end ({rp.channel_end_lat_deg:.2f}, {rp.channel_end_lon_deg:.2f}) and "
                     f"the berth, {rp.length_nm:.0f} NM at {RIVER_TRANSIT_KN:g} kn, takes "
                     f"{rp.hours:.1f} h each way (pilotage, not planned): the call's window "
                     "is moved to the seaward end and its stay there lengthened by both")
        rows.append({"port": port.name, "end": "call", "length_nm": rp.length_nm,
                     "speed_kn": RIVER_TRANSIT_KN, "hours": rp.hours,
                     "channel_end": [rp.channel_end_lat_deg, rp.channel_end_lon_deg]})
    return out, notes, rows


def with_river_passages(plan, rows: list[dict]):
    """The plan with `extra["river_passages"]`; the destination row gets the ETA at the
    berth (the planned arrival at the seaward end plus the river passage)."""
    import dataclasses

    if not rows:
        return plan
    done = []
    for r in rows:
        r = dict(r)
        if r["end"] == "arrival":
            r["berth_eta_s"] = plan.eta_s + r["hours"] * 3600.0
            r["berth_eta"] = _iso(r["berth_eta_s"])
        done.append(r)
    return dataclasses.replace(plan, extra={**plan.extra, "river_passages": done})
