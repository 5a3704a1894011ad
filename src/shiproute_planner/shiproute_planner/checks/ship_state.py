"""Checks of an own-ship state (fix) before the planner takes it as the voyage's start.

Position and time are required: finite, latitude within +-90, longitude within +-180 (the
message's convention), time in 1990..2100 and, when the clock is known, not older than
`max_age_s` nor further ahead than `max_lead_s`. Every other value is optional (NaN =
unknown) but, when given, must be finite and physically possible. Raises `ShipStateError`
naming the field, its value and the accepted range.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import ShipStateError
from .forecast_wire import EARLIEST_TIME_S, LATEST_TIME_S

#: optional values: (name, lowest, highest, unit); NaN means unknown and passes
OPTIONAL_RANGES: tuple[tuple[str, float, float, str], ...] = (
    ("sog_kn", 0.0, 60.0, "kn"),          # fastest merchant ships ~40 kn; AIS caps at 102.2
    ("cog_deg", 0.0, 360.0, "deg"),
    ("heading_deg", 0.0, 360.0, "deg"),
    ("stw_kn", -15.0, 60.0, "kn"),        # astern through the water allowed
    ("shaft_rpm", -300.0, 300.0, "rpm"),  # large two-strokes 60-130 rpm, medium-speed gears
    ("draft_fore_m", 0.0, 35.0, "m"),     # deepest laden ULCC ~25 m
    ("draft_aft_m", 0.0, 35.0, "m"),
    ("fuel_rate_t_per_h", 0.0, 30.0, "t/h"),
)


@dataclass(frozen=True)
class ShipFix:
    """The checked part of a ship state: position [deg] and time (POSIX s, UTC)."""

    lat_deg: float
    lon_deg: float
    time_s: float


def check_ship_state(lat_deg: float, lon_deg: float, time_s: float,
                     optional: dict[str, float] | None = None, *, clock_s: float | None = None,
                     max_age_s: float = 366 * 86400.0, max_lead_s: float = 3600.0) -> ShipFix:
    """The fix of a ship state, or ShipStateError naming what is wrong. `clock_s` is the
    node's clock (None or <= 0 when not known yet, e.g. simulated time before /clock)."""
    if not (math.isfinite(lat_deg) and -90.0 <= lat_deg <= 90.0):
        raise ShipStateError(f"ship state latitude_deg = {lat_deg!r}; expected -90..90")
    if not (math.isfinite(lon_deg) and -180.0 <= lon_deg <= 180.0):
        raise ShipStateError(f"ship state longitude_deg = {lon_deg!r}; expected -180..180")
    if not (math.isfinite(time_s) and EARLIEST_TIME_S <= time_s <= LATEST_TIME_S):
        raise ShipStateError(f"ship state stamp = {time_s!r} s; expected a UTC time between "
                             "1990-01-01 and 2100-01-01 (an unset stamp is 1970)")
    if clock_s is not None and math.isfinite(clock_s) and clock_s > 0:
        if time_s < clock_s - max_age_s:
            raise ShipStateError(
                f"ship state stamp {time_s:.0f} s is {(clock_s - time_s) / 3600:.1f} h older "
                f"than the clock; expected at most {max_age_s / 3600:g} h old")
        if time_s > clock_s + max_lead_s:
            raise ShipStateError(
                f"ship state stamp {time_s:.0f} s is {(time_s - clock_s) / 3600:.2f} h ahead "
                f"of the clock; expected at most {max_lead_s / 3600:g} h ahead")
    for name, lo, hi, unit in OPTIONAL_RANGES:
        value = (optional or {}).get(name, math.nan)
        if math.isnan(value):
            continue
        if not lo <= value <= hi:  # inf fails here too
            raise ShipStateError(f"ship state {name} = {value!r}; expected {lo:g}..{hi:g} "
                                 f"{unit} or NaN (unknown)")
    return ShipFix(float(lat_deg), float(lon_deg), float(time_s))
