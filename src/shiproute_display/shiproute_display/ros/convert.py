"""The only place where ROS messages become display values and Foxglove messages are made.

Decoding never raises anything but MalformedMessageError, so the node counts a bad message
and goes on. Forecast fields are read with `shiproute_weather.wire.packing` (packed 16-bit
or float32, the weather node's wire format) without the weather package's xarray side.
"""

from __future__ import annotations

import json
import math
from typing import Any

import numpy as np
from builtin_interfaces.msg import Time
from sensor_msgs.msg import NavSatFix, NavSatStatus
from shiproute_weather.errors import SliceError
from shiproute_weather.wire.packing import PackedField, field_values, unpack_field
from std_msgs.msg import Float64

from foxglove_msgs.msg import GeoJSON
from shiproute_msgs.msg import ForecastCycle, ForecastSlice, RoutePlan, RpmProfile, ShipState

from ..errors import MalformedMessageError
from ..forecast_view import HS_NAME, WIND_U_NAME, WIND_V_NAME, GridSpec, SliceView, thin_slice
from ..model import (
    CycleInfo,
    EnsembleSpread,
    Plan,
    Profile,
    ShipFix,
    Stage,
    Waypoint,
    check_fix,
    check_plan,
    check_profile,
)

DISPLAY_FIELDS = (HS_NAME, WIND_U_NAME, WIND_V_NAME)


def posix_s(t: Time) -> float:
    """builtin_interfaces/Time -> POSIX seconds (zero time -> NaN: 'not set')."""
    if t.sec == 0 and t.nanosec == 0:
        return math.nan
    return t.sec + t.nanosec * 1e-9


def time_msg(t_s: float) -> Time:
    """POSIX seconds -> builtin_interfaces/Time (non-finite -> zero)."""
    if not math.isfinite(t_s):
        return Time()
    ns = round(t_s * 1e9)
    return Time(sec=int(ns // 1_000_000_000), nanosec=int(ns % 1_000_000_000))


def plan_from_msg(msg: RoutePlan) -> Plan:
    """RoutePlan -> checked Plan (MalformedMessageError when it cannot be drawn)."""
    wps = tuple(Waypoint(
        float(w.latitude_deg), float(w.longitude_deg), posix_s(w.time), float(w.heading_deg),
        float(w.shaft_rpm), float(w.sog_kn), float(w.stw_kn), float(w.leg_distance_nm),
        float(w.leg_duration_s), float(w.leg_fuel_t), float(w.hs_m), float(w.wind_speed_m_s),
        int(w.constraint_flags)) for w in msg.waypoints)
    plan = Plan(
        plan_id=str(msg.plan_id), cycle_id=str(msg.cycle_id), method=str(msg.method),
        objective=str(msg.objective), ship_name=str(msg.ship_name),
        trigger=str(getattr(msg, "trigger", "")), stamp_s=posix_s(msg.header.stamp),
        departure_s=posix_s(msg.departure_time), rta_s=posix_s(msg.rta), eta_s=posix_s(msg.eta),
        feasible=bool(msg.feasible), infeasible_reasons=tuple(msg.infeasible_reasons),
        warnings=tuple(msg.warnings), total_fuel_t=float(msg.total_fuel_t),
        total_distance_nm=float(msg.total_distance_nm),
        baseline_fuel_t=float(msg.baseline_fuel_t), compute_time_s=float(msg.compute_time_s),
        waypoints=wps, ensemble=_spread(msg))
    return check_plan(plan)


def _spread(msg: RoutePlan) -> EnsembleSpread | None:
    """The plan's ensemble spread, None when it was made on one forecast."""
    members = int(getattr(msg, "ensemble_members", 0))
    if members < 1:
        return None
    floats = lambda name: tuple(float(v) for v in getattr(msg, name))  # noqa: E731
    return EnsembleSpread(
        members, str(msg.risk_measure), floats("fuel_quantiles_t"),
        tuple(posix_s(t) for t in msg.eta_quantiles), float(msg.p_hs_violation),
        float(msg.p_late), floats("leg_hs_min_m"), floats("leg_hs_median_m"),
        floats("leg_hs_max_m"), floats("leg_wind_min_m_s"), floats("leg_wind_max_m_s"))


def profile_from_msg(msg: RpmProfile) -> Profile:
    """RpmProfile -> checked Profile."""
    return check_profile(Profile(str(msg.plan_id), tuple(
        Stage(posix_s(s.start_time), float(s.duration_s), float(s.shaft_rpm),
              float(s.heading_deg)) for s in msg.stages)))


def fix_from_msg(msg: ShipState) -> ShipFix:
    """ShipState -> checked ShipFix."""
    return check_fix(ShipFix(
        posix_s(msg.header.stamp), float(msg.latitude_deg), float(msg.longitude_deg),
        float(msg.sog_kn), float(msg.cog_deg), float(msg.heading_deg), float(msg.shaft_rpm),
        float(msg.fuel_rate_t_per_h), int(msg.mmsi)))


def cycle_from_msg(msg: ForecastCycle) -> CycleInfo:
    """ForecastCycle -> CycleInfo."""
    if not msg.cycle_id or msg.slice_count < 1:
        raise MalformedMessageError(
            f"ForecastCycle {msg.cycle_id!r} announces {msg.slice_count} slices")
    members = max(1, int(msg.member_count))
    if msg.slice_count % members:
        raise MalformedMessageError(
            f"ForecastCycle {msg.cycle_id!r}: {msg.slice_count} slices cannot be split into "
            f"{members} members")
    return CycleInfo(str(msg.cycle_id), posix_s(msg.reference_time),
                     posix_s(msg.first_valid_time), posix_s(msg.last_valid_time),
                     float(msg.step_s), int(msg.slice_count), str(msg.source), members,
                     tuple(str(x) for x in msg.member_labels), str(msg.member_kind))


def slice_view_from_msg(msg: ForecastSlice, max_cells: int) -> SliceView:
    """ForecastSlice -> the page's thinned SliceView (Hs and wind decoded, others skipped)."""
    grid = GridSpec(float(msg.lat0_deg), float(msg.dlat_deg), int(msg.n_lat),
                    float(msg.lon0_deg), float(msg.dlon_deg), int(msg.n_lon))
    fields: dict[str, np.ndarray] = {}
    for f in msg.fields:
        if f.name not in DISPLAY_FIELDS:
            continue
        try:
            v = field_values(f)
        except SliceError as err:
            raise MalformedMessageError(f"forecast slice {msg.slice_index}: {err}") from err
        fields[f.name] = unpack_field(v) if isinstance(v, PackedField) else np.asarray(v)
    return thin_slice(int(msg.slice_index), posix_s(msg.valid_time), grid, fields, max_cells,
                      member=int(msg.member))


def navsatfix(lat_deg: float, lon_deg: float, t_s: float, frame_id: str) -> NavSatFix:
    """A position as sensor_msgs/NavSatFix (no altitude, covariance unknown)."""
    m = NavSatFix()
    m.header.stamp = time_msg(t_s)
    m.header.frame_id = frame_id
    m.status.status = NavSatStatus.STATUS_FIX
    m.status.service = NavSatStatus.SERVICE_GPS
    m.latitude = float(lat_deg)
    m.longitude = float((lon_deg + 180.0) % 360.0 - 180.0)
    m.altitude = math.nan
    m.position_covariance_type = NavSatFix.COVARIANCE_TYPE_UNKNOWN
    return m


def geojson_msg(collection: dict[str, Any]) -> GeoJSON:
    """A GeoJSON object as foxglove_msgs/GeoJSON."""
    return GeoJSON(geojson=json.dumps(collection, separators=(",", ":"), allow_nan=False))


def float64_msg(value: float) -> Float64:
    """A plottable number."""
    return Float64(data=float(value))
