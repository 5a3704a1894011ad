"""ROS-free own-ship state record, its rosbags (CDR) form, and NavSatFix -> ShipState conversion."""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from typing import Any

from rosbags.typesys.store import Typestore
from shiproute_core.units import M_S_PER_KNOT

from .typestore import SHIP_STATE_TYPE

NAN = math.nan
NAV_STATUS_UNDEFINED = 15
VELOCITY_MAX_AGE_NS = 5_000_000_000  # a velocity older than this is not used for SOG/COG
FIX_MAX_GAP_NS = 600_000_000_000  # fixes further apart than this give no derived SOG/COG


@dataclass(frozen=True)
class ShipStateRecord:
    """One ShipState (units as in ShipState.msg); NaN / 0 for unknown values."""

    time_ns: int
    latitude_deg: float
    longitude_deg: float
    sog_kn: float = NAN
    cog_deg: float = NAN
    heading_deg: float = NAN
    stw_kn: float = NAN
    shaft_rpm: float = NAN
    draft_fore_m: float = NAN
    draft_aft_m: float = NAN
    fuel_rate_t_per_h: float = NAN
    mmsi: int = 0
    nav_status: int = NAV_STATUS_UNDEFINED


_FLOAT_FIELDS = [f.name for f in fields(ShipStateRecord) if f.type == "float"]


def to_rosbags(store: Typestore, rec: ShipStateRecord, frame_id: str = "wgs84") -> Any:
    """rosbags ``shiproute_msgs/msg/ShipState`` object for ``rec``."""
    time_cls = store.types["builtin_interfaces/msg/Time"]
    header = store.types["std_msgs/msg/Header"](
        stamp=time_cls(sec=rec.time_ns // 1_000_000_000, nanosec=rec.time_ns % 1_000_000_000),
        frame_id=frame_id,
    )
    kwargs = {name: float(getattr(rec, name)) for name in _FLOAT_FIELDS}
    return store.types[SHIP_STATE_TYPE](
        header=header, mmsi=int(rec.mmsi), nav_status=int(rec.nav_status), **kwargs
    )


def from_rosbags(msg: Any) -> ShipStateRecord:
    """ShipStateRecord of a rosbags (or rclpy) ShipState message."""
    stamp = msg.header.stamp
    kwargs = {name: float(getattr(msg, name)) for name in _FLOAT_FIELDS}
    return ShipStateRecord(
        time_ns=int(stamp.sec) * 1_000_000_000 + int(stamp.nanosec),
        mmsi=int(msg.mmsi),
        nav_status=int(msg.nav_status),
        **kwargs,
    )


class NavFixConverter:
    """Builds ShipState records from NavSatFix fixes plus optional ENU velocity messages.

    SOG/COG come from the newest velocity (TwistStamped-style, x east / y north [m/s]) when it
    is at most 5 s old, otherwise from the previous valid fix (great-circle distance over time).
    Fixes with status -1 (no fix) or non-finite positions are rejected and counted.
    """

    def __init__(self, mmsi: int = 0) -> None:
        self.mmsi = mmsi
        self.rejected = 0
        self._prev: tuple[int, float, float] | None = None
        self._vel: tuple[int, float, float] | None = None

    def feed_velocity(self, time_ns: int, east_m_s: float, north_m_s: float) -> None:
        """Remember a ground velocity (ENU) for the next fixes."""
        self._vel = (time_ns, east_m_s, north_m_s)

    def feed_fix(self, time_ns: int, lat_deg: float, lon_deg: float,
                 status: int = 0) -> ShipStateRecord | None:
        """ShipStateRecord for one fix, or None when the fix is unusable."""
        if status < 0 or not (math.isfinite(lat_deg) and math.isfinite(lon_deg)) or not (
            -90.0 <= lat_deg <= 90.0 and -180.0 <= lon_deg <= 360.0
        ):
            self.rejected += 1
            return None
        lon_deg = (lon_deg + 180.0) % 360.0 - 180.0
        sog_kn, cog_deg = NAN, NAN
        if self._vel is not None and abs(time_ns - self._vel[0]) <= VELOCITY_MAX_AGE_NS:
            _, ve, vn = self._vel
            sog_kn = math.hypot(ve, vn) / M_S_PER_KNOT
            cog_deg = math.degrees(math.atan2(ve, vn)) % 360.0
        elif self._prev is not None and 0 < time_ns - self._prev[0] <= FIX_MAX_GAP_NS:
            t0, lat0, lon0 = self._prev
            # imported here: pyproj is only needed when fixes are converted, so a replay of
            # ShipState bags does not load it
            from shiproute_core.geodesy import bearing_deg, distance_m

            dist = float(distance_m(lon0, lat0, lon_deg, lat_deg))
            sog_kn = dist / ((time_ns - t0) * 1e-9) / M_S_PER_KNOT
            cog_deg = float(bearing_deg(lon0, lat0, lon_deg, lat_deg)) if dist > 0 else NAN
        self._prev = (time_ns, lat_deg, lon_deg)
        return ShipStateRecord(
            time_ns=time_ns, latitude_deg=lat_deg, longitude_deg=lon_deg,
            sog_kn=sog_kn, cog_deg=cog_deg, mmsi=self.mmsi,
        )
