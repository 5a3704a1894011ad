"""Plain records shared by the AIS readers and the track cleaner."""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass, field

NAN = math.nan


@dataclass(frozen=True)
class AisFix:
    """One position report as received (AIS 'not available' codes still in place)."""

    mmsi: int
    time_ns: int
    lat_deg: float
    lon_deg: float
    sog_kn: float = NAN
    cog_deg: float = NAN
    heading_deg: float = NAN
    nav_status: int = 15


@dataclass(frozen=True)
class AisStatic:
    """Static and voyage data (type 5 / CSV columns) of one vessel at one time."""

    mmsi: int
    time_ns: int
    draught_m: float = NAN
    name: str = ""
    imo: int = 0


@dataclass
class AisInput:
    """Everything read from one AIS source plus the counts of lines/rows rejected by reason."""

    fixes: list[AisFix] = field(default_factory=list)
    statics: list[AisStatic] = field(default_factory=list)
    rejected: Counter = field(default_factory=Counter)
    notes: Counter = field(default_factory=Counter)  # values kept but marked n/a, by reason
