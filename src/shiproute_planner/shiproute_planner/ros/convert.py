"""The only place where planner values become ROS messages (and ship states come back).

`nav_msgs/Path` poses are in the REP 105 ``earth`` frame (WGS 84 ECEF metres, see
`path_frame`), stamped with the planned time at each node; `RpmProfile` holds one stage per leg;
`RoutePlan` copies the frozen plan field by field. Forecast slices come in as `SliceFields`
whose arrays are views on the message's buffers (no copy; float32 or 16-bit packed fields).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from builtin_interfaces.msg import Time
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Path
from shiproute_weather.contract.canonical import Grid
from shiproute_weather.errors import SliceError
from shiproute_weather.wire.packing import field_values

from shiproute_msgs.action import PlanRoute
from shiproute_msgs.msg import ForecastSlice, RouteWaypoint, RpmProfile, RpmStage, ShipState
from shiproute_msgs.msg import RoutePlan as RoutePlanMsg

from ..path_frame import track_to_ecef
from ..plan_types import RoutePlan
from ..voyage.port_calls import PortCall
from ..voyage_request import VoyageChange
from .cycle_packer import SliceFields

EARTH_FRAME = "earth"


def time_msg(posix_s: float) -> Time:
    """POSIX seconds (UTC) -> builtin_interfaces/Time (NaN/inf -> zero time)."""
    if not math.isfinite(posix_s):
        return Time()
    ns = round(posix_s * 1e9)
    return Time(sec=int(ns // 1_000_000_000), nanosec=int(ns % 1_000_000_000))


def posix_s(stamp: Time) -> float:
    """builtin_interfaces/Time -> POSIX seconds."""
    return stamp.sec + stamp.nanosec * 1e-9


def plan_to_msg(plan: RoutePlan, stamp: Time) -> RoutePlanMsg:
    """Frozen plan -> shiproute_msgs/RoutePlan."""
    msg = RoutePlanMsg()
    msg.header.stamp = stamp
    msg.header.frame_id = "wgs84"
    msg.plan_id = plan.plan_id
    msg.cycle_id = plan.cycle_id
    msg.method = plan.method
    msg.seed_source = plan.seed_source
    msg.objective = plan.objective
    msg.ship_name = plan.ship_name
    msg.departure_time = time_msg(plan.departure_s)
    msg.rta = time_msg(plan.rta_s)
    msg.eta = time_msg(plan.eta_s)
    msg.feasible = bool(plan.feasible)
    msg.infeasible_reasons = list(plan.infeasible_reasons)
    msg.warnings = list(plan.warnings)
    msg.total_fuel_t = float(plan.total_fuel_t)
    msg.total_distance_nm = float(plan.total_distance_nm)
    msg.total_time_s = float(plan.total_time_s)
    msg.baseline_fuel_t = float(plan.baseline_fuel_t)
    msg.baseline_feasible = bool(plan.baseline_feasible)
    msg.compute_time_s = float(plan.compute_time_s)
    msg.waypoints = [_waypoint_msg(w) for w in plan.waypoints]
    calls = plan.extra.get("port_calls", ())
    msg.call_ports = [str(r["port"]) for r in calls]
    msg.call_arrivals = [time_msg(float(r["arrival_s"])) for r in calls]
    msg.call_departures = [time_msg(float(r["departure_s"])) for r in calls]
    _ensemble_fields(msg, plan)
    return msg


def _ensemble_fields(msg: RoutePlanMsg, plan: RoutePlan) -> None:
    """The plan's spread over ensemble members (empty / NaN for one forecast)."""
    msg.ensemble_members = int(plan.ensemble_members)
    msg.risk_measure = plan.risk_measure
    msg.fuel_quantiles_t = [float(v) for v in plan.fuel_quantiles_t]
    msg.eta_quantiles = [time_msg(float(t)) for t in plan.eta_quantiles_s]
    msg.p_hs_violation = float(plan.p_hs_violation)
    msg.p_late = float(plan.p_late)
    for name, rows in (("hs", plan.leg_hs_spread_m), ("wind", plan.leg_wind_spread_m_s)):
        unit = "m" if name == "hs" else "m_s"
        for k, stat in enumerate(("min", "median", "max")):
            setattr(msg, f"leg_{name}_{stat}_{unit}", [float(r[k]) for r in rows])


def _waypoint_msg(w) -> RouteWaypoint:
    m = RouteWaypoint()
    m.latitude_deg = float(w.lat_deg)
    m.longitude_deg = float(w.lon_deg)
    m.time = time_msg(w.time_s)
    for name in (
        "heading_deg", "stw_kn", "sog_kn", "leg_distance_nm", "leg_duration_s", "leg_fuel_t",
        "brake_power_kw", "hs_m", "wave_from_deg", "wind_speed_m_s", "wind_from_deg",
        "p_slamming", "p_deck_wetness", "p_propeller_emergence", "min_depth_m", "ukc_m",
    ):
        setattr(m, name, float(getattr(w, name)))
    m.shaft_rpm = float(w.shaft_rpm)
    m.constraint_flags = int(w.constraint_flags)
    return m


def plan_to_rpm_profile(plan: RoutePlan, stamp: Time) -> RpmProfile:
    """The engine-room schedule: one stage per leg (start time, duration, RPM, heading)."""
    msg = RpmProfile()
    msg.header.stamp = stamp
    msg.header.frame_id = "wgs84"
    msg.plan_id = plan.plan_id
    for w in plan.waypoints[:-1]:
        msg.stages.append(
            RpmStage(
                start_time=time_msg(w.time_s),
                duration_s=float(w.leg_duration_s),
                shaft_rpm=float(w.shaft_rpm),
                heading_deg=float(w.heading_deg),
            )
        )
    return msg


def plan_to_path(plan: RoutePlan, stamp: Time) -> Path:
    """Planned track as nav_msgs/Path in the REP 105 earth frame (ECEF), one pose per node.

    The arrival node has no leg of its own; it carries the heading of the last leg.
    """
    lat = [w.lat_deg for w in plan.waypoints]
    lon = [w.lon_deg for w in plan.waypoints]
    heading = [w.heading_deg for w in plan.waypoints]
    if len(heading) > 1 and not math.isfinite(heading[-1]):
        heading[-1] = heading[-2]
    poses = track_to_ecef(lat, lon, heading)
    path = Path()
    path.header.stamp = stamp
    path.header.frame_id = EARTH_FRAME
    for i, w in enumerate(plan.waypoints):
        pose = PoseStamped()
        pose.header.stamp = time_msg(w.time_s)
        pose.header.frame_id = EARTH_FRAME
        pose.pose.position.x = float(poses.x_m[i])
        pose.pose.position.y = float(poses.y_m[i])
        pose.pose.position.z = float(poses.z_m[i])
        qx, qy, qz, qw = (float(v) for v in poses.quaternion_xyzw[i])
        pose.pose.orientation.x, pose.pose.orientation.y = qx, qy
        pose.pose.orientation.z, pose.pose.orientation.w = qz, qw
        path.poses.append(pose)
    return path


def ship_position(msg: ShipState) -> tuple[float, float, float] | None:
    """(lat_deg, lon_deg, time POSIX s) of a ShipState, None when the fix is unusable."""
    lat, lon = float(msg.latitude_deg), float(msg.longitude_deg)
    if not (math.isfinite(lat) and math.isfinite(lon)) or abs(lat) > 90.0 or abs(lon) > 180.0:
        return None
    return lat, lon, posix_s(msg.header.stamp)


def slice_fields(msg: ForecastSlice) -> SliceFields:
    """ROS-free view of a ForecastSlice; the field arrays share the message's buffers: float32
    `data`, or the 16-bit `packed` codes with their scaling (decoded when packed into the
    sampler). A field with both or neither is passed on as a problem for the packer to
    reject (this runs in a subscription callback: it must not raise)."""
    grid = Grid(float(msg.lat0_deg), float(msg.dlat_deg), int(msg.n_lat), float(msg.lon0_deg),
                float(msg.dlon_deg), int(msg.n_lon))
    fields = []
    problems = []
    for f in msg.fields:
        try:
            fields.append((f.name, field_values(f)))
        except SliceError as err:
            problems.append(str(err))
            fields.append((f.name, np.frombuffer(f.data, dtype=np.float32)))
    return SliceFields(msg.cycle_id, int(msg.slice_index), int(msg.slice_count),
                       posix_s(msg.valid_time), grid, tuple(fields), tuple(problems),
                       posix_s(msg.reference_time), str(msg.publication_id),
                       int(msg.member), max(1, int(msg.member_count)), str(msg.member_label))


def cycle_record(msg: Any) -> dict:
    """The forecast record of a ForecastCycle announcement (files, field sources, load notes)
    that a plan states (`forecast_statement`)."""
    sources = list(getattr(msg, "field_sources", []) or [])
    fields = {str(n): {"source_file": str(sources[k]) if k < len(sources) else ""}
              for k, n in enumerate(msg.fields)}
    return {"cycle_id": str(msg.cycle_id), "source_files": [str(f) for f in msg.source_files],
            "fields": fields, "notes": [str(n) for n in getattr(msg, "notes", []) or []],
            "member_count": max(1, int(getattr(msg, "member_count", 1) or 1)),
            "member_labels": [str(x) for x in getattr(msg, "member_labels", []) or []],
            "member_kind": str(getattr(msg, "member_kind", "") or "")}


def port_call_from_msg(msg: Any) -> PortCall:
    """shiproute_msgs/PortCall -> PortCall (a zero time is an open window end)."""
    def when(stamp: Time) -> float | None:
        return None if stamp.sec == 0 and stamp.nanosec == 0 else posix_s(stamp)

    return PortCall(str(msg.port).strip(), when(msg.earliest_arrival), when(msg.latest_arrival),
                    float(msg.berth_hours) * 3600.0)
#: the optional fields of a ShipState (NaN when not reported), checked for range when present
SHIP_STATE_OPTIONALS = ("sog_kn", "cog_deg", "heading_deg", "stw_kn", "shaft_rpm",
                        "draft_fore_m", "draft_aft_m", "fuel_rate_t_per_h")


def ship_state_optionals(msg: ShipState) -> dict[str, float]:
    """The optional fields of a ShipState by name (NaN when not reported)."""
    return {name: float(getattr(msg, name)) for name in SHIP_STATE_OPTIONALS}


def voyage_request(req: Any) -> VoyageChange:
    """The voyage of a SetVoyage request, not yet checked."""
    return VoyageChange(
        destination=req.destination, destination_lat_deg=float(req.destination_lat_deg),
        destination_lon_deg=float(req.destination_lon_deg), rta_s=posix_s(req.rta),
        ship=req.ship, objective=req.objective,
        port_calls=tuple(port_call_from_msg(c) for c in req.port_calls))


def plan_feedback(progress: dict[str, float], elapsed_s: float) -> Any:
    """PlanRoute feedback from the planner's progress values."""
    fb = PlanRoute.Feedback()
    fb.generation = int(progress.get("generation", 0))
    fb.evaluations = int(progress.get("evaluations", 0))
    fb.best_fuel_t = float(progress.get("best_objective", math.nan))
    fb.elapsed_s = elapsed_s
    return fb


def plan_messages(plan: RoutePlan, stamp: Time, trigger: str) -> tuple[Path, RpmProfile, Any]:
    """The three messages of a published plan: Path, RpmProfile and RoutePlan, the last with
    what triggered the plan (shown in the bridge display's re-plan history)."""
    plan_msg = plan_to_msg(plan, stamp)
    plan_msg.trigger = trigger
    return plan_to_path(plan, stamp), plan_to_rpm_profile(plan, stamp), plan_msg
