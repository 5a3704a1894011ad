"""Port calls of a multi-port voyage: an arrival window (earliest/latest), a berth time, or
no fixed time, parsed from `PORT[@EARLIEST..LATEST][+BERTH_H]` text (CLI `--via`).

Times are ISO 8601 UTC or offsets after departure ('3d', '36h'); either end of a window may
be left out ('@..2026-06-05T00:00Z', '@3d..'); a single time ('@3d') is a latest arrival,
which is what the old `PORT@TIME` form meant. Malformed text raises InvalidVoyageError naming
the port call and what is wrong.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from datetime import UTC, datetime

from ..errors import InvalidVoyageError

_OFFSET = re.compile(r"^\s*(\d+(?:\.\d*)?)\s*([smhd])\s*$")
_BERTH = re.compile(r"\+\s*([^+:]*?)\s*h?\s*$")  # "+12", "+12h"; not "+00:00"
_UNIT_S = {"s": 1.0, "m": 60.0, "h": 3600.0, "d": 86400.0}
MAX_BERTH_H = 24.0 * 60.0  # two months alongside is no longer a port call


@dataclass(frozen=True)
class PortCall:
    """One intermediate port: name, arrival window [POSIX s UTC; None = open], berth [s]."""

    port: str
    earliest_s: float | None = None
    latest_s: float | None = None
    berth_s: float = 0.0

    @property
    def fixed(self) -> bool:
        """True when the call has a window or a berth time (else the schedule is free)."""
        return self.earliest_s is not None or self.latest_s is not None or self.berth_s > 0

    def label(self) -> str:
        """The call as a user would write it back (ISO times, berth in hours)."""
        text = self.port
        if self.earliest_s is not None or self.latest_s is not None:
            text += f"@{_iso(self.earliest_s)}..{_iso(self.latest_s)}"
        if self.berth_s > 0:
            text += f"+{self.berth_s / 3600.0:g}"
        return text


def _iso(t_s: float | None) -> str:
    if t_s is None:
        return ""
    return datetime.fromtimestamp(t_s, UTC).strftime("%Y-%m-%dT%H:%M:%SZ")


def _time_s(text: str, depart_s: float, what: str) -> float:
    """ISO 8601 UTC time or an offset after departure -> POSIX s (InvalidVoyageError)."""
    m = _OFFSET.match(text)
    if m:
        return depart_s + float(m.group(1)) * _UNIT_S[m.group(2)]
    try:
        value = datetime.fromisoformat(text.strip().replace("Z", "+00:00"))
    except ValueError:
        raise InvalidVoyageError(
            f"{what} {text!r}: use an ISO 8601 UTC time (2026-06-05T12:00Z) or an offset "
            "after departure (3d, 36h)") from None
    if value.tzinfo is None:
        value = value.replace(tzinfo=UTC)
    return value.timestamp()


def parse_port_call(text: str, depart_s: float) -> PortCall:
    """`PORT[@EARLIEST..LATEST][+BERTH_H]` -> PortCall (offsets count from `depart_s`)."""
    raw = str(text)
    m = _BERTH.search(raw)
    head, berth_text = (raw[: m.start()], m.group(1)) if m else (raw, "")
    name, at, window = head.partition("@")
    name = name.strip()
    if not name:
        raise InvalidVoyageError(f"port call {raw!r} names no port")
    berth_s = 0.0
    if m:
        try:
            berth_h = float(berth_text)
        except ValueError:
            raise InvalidVoyageError(
                f"port call {raw!r}: berth time {berth_text!r} is not a number of hours"
            ) from None
        if not (math.isfinite(berth_h) and 0.0 <= berth_h <= MAX_BERTH_H):
            raise InvalidVoyageError(
                f"port call {raw!r}: berth time {berth_text!r} h must be in 0..{MAX_BERTH_H:g}")
        berth_s = berth_h * 3600.0
    earliest = latest = None
    if at:
        if not window.strip():
            raise InvalidVoyageError(f"port call {raw!r}: '@' needs a time or a window")
        if ".." in window:
            lo, _, hi = window.partition("..")
            earliest = _time_s(lo, depart_s, f"{name} earliest arrival") if lo.strip() else None
            latest = _time_s(hi, depart_s, f"{name} latest arrival") if hi.strip() else None
        else:
            latest = _time_s(window, depart_s, f"{name} arrival")
    return check_port_call(PortCall(name, earliest, latest, berth_s), depart_s)


def check_port_call(call: PortCall, depart_s: float) -> PortCall:
    """The call itself when its window is well formed, else InvalidVoyageError naming it."""
    for what, t in (("earliest", call.earliest_s), ("latest", call.latest_s)):
        if t is not None and not math.isfinite(t):
            raise InvalidVoyageError(f"port call {call.port}: {what} arrival is not finite")
    if not (math.isfinite(call.berth_s) and 0.0 <= call.berth_s <= MAX_BERTH_H * 3600.0):
        raise InvalidVoyageError(f"port call {call.port}: berth time {call.berth_s / 3600:g} h "
                                 f"must be in 0..{MAX_BERTH_H:g} h")
    if call.latest_s is not None and call.latest_s <= depart_s:
        raise InvalidVoyageError(
            f"port call {call.port}: latest arrival {_iso(call.latest_s)} is not after the "
            f"departure {_iso(depart_s)}")
    if (call.earliest_s is not None and call.latest_s is not None
            and call.earliest_s > call.latest_s):
        raise InvalidVoyageError(
            f"port call {call.port}: earliest arrival {_iso(call.earliest_s)} is after the "
            f"latest {_iso(call.latest_s)}")
    return call


def parse_port_calls(items: list[str] | tuple[str, ...], depart_s: float) -> tuple[PortCall, ...]:
    """Every `--via` item parsed (see `parse_port_call`)."""
    return tuple(parse_port_call(item, depart_s) for item in items)
