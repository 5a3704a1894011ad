"""Frozen values the display shows: plan, engine-room schedule, own-ship fix, forecast cycle.

Built from ROS messages by `convert` and checked here (`check_plan`, `check_fix`), so a message
that cannot be shown is counted as malformed instead of reaching the page. Units in names,
times POSIX seconds UTC, latitudes/longitudes WGS 84 degrees.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from itertools import pairwise

from .errors import MalformedMessageError


@dataclass(frozen=True)
class Waypoint:
    """A plan node and the leg that starts there (leg values NaN on the arrival node)."""

    lat_deg: float
    lon_deg: float
    time_s: float
    heading_deg: float
    shaft_rpm: float
    sog_kn: float
    stw_kn: float
    leg_distance_nm: float
    leg_duration_s: float
    leg_fuel_t: float
    hs_m: float
    wind_speed_m_s: float
    constraint_flags: int


@dataclass(frozen=True)
class EnsembleSpread:
    """What a plan sailed on an ensemble states of its spread (RoutePlan issue-19 fields)."""

    members: int
    risk_measure: str  # mean | cvar:ALPHA | worst; '' = planned on the members' mean
    fuel_quantiles_t: tuple[float, ...]  # P10, P50, P90 [t]
    eta_quantiles_s: tuple[float, ...]  # P10, P50, P90 (POSIX s)
    p_hs_violation: float
    p_late: float
    leg_hs_min_m: tuple[float, ...]
    leg_hs_median_m: tuple[float, ...]
    leg_hs_max_m: tuple[float, ...]
    leg_wind_min_m_s: tuple[float, ...]
    leg_wind_max_m_s: tuple[float, ...]


@dataclass(frozen=True)
class Plan:
    """What the page and Foxglove need of a RoutePlan."""

    plan_id: str
    cycle_id: str
    method: str
    objective: str
    ship_name: str
    trigger: str
    stamp_s: float
    departure_s: float
    rta_s: float
    eta_s: float
    feasible: bool
    infeasible_reasons: tuple[str, ...]
    warnings: tuple[str, ...]
    total_fuel_t: float
    total_distance_nm: float
    baseline_fuel_t: float
    compute_time_s: float
    waypoints: tuple[Waypoint, ...]
    ensemble: EnsembleSpread | None = None  # the spread over forecast members (None: one)

    @property
    def fuel_saving_t(self) -> float:
        """Baseline fuel minus plan fuel [t]; NaN without a baseline."""
        if not (math.isfinite(self.baseline_fuel_t) and self.baseline_fuel_t > 0):
            return math.nan
        return self.baseline_fuel_t - self.total_fuel_t


@dataclass(frozen=True)
class Stage:
    """One engine-room stage: hold `shaft_rpm` and `heading_deg` from `start_s` for `duration_s`."""

    start_s: float
    duration_s: float
    shaft_rpm: float
    heading_deg: float


@dataclass(frozen=True)
class Profile:
    """The RpmProfile of a plan."""

    plan_id: str
    stages: tuple[Stage, ...]


@dataclass(frozen=True)
class ShipFix:
    """Own-ship state as shown (NaN = unknown)."""

    time_s: float
    lat_deg: float
    lon_deg: float
    sog_kn: float
    cog_deg: float
    heading_deg: float
    shaft_rpm: float
    fuel_rate_t_per_h: float
    mmsi: int


@dataclass(frozen=True)
class CycleInfo:
    """A forecast cycle announcement."""

    cycle_id: str
    reference_s: float
    first_valid_s: float
    last_valid_s: float
    step_s: float
    slice_count: int
    source: str
    member_count: int = 1  # members of the cycle; slice_count = member_count x valid times
    member_labels: tuple[str, ...] = ()
    member_kind: str = ""  # "ensemble" | "multi-model" ('' deterministic)

    @property
    def times_per_member(self) -> int:
        """Valid times of each member."""
        return self.slice_count // max(1, self.member_count)


def _finite_position(lat: float, lon: float) -> bool:
    return math.isfinite(lat) and math.isfinite(lon) and abs(lat) <= 90.0 and abs(lon) <= 360.0


def check_plan(plan: Plan) -> Plan:
    """The plan itself when it can be drawn; MalformedMessageError naming what is wrong."""
    n = len(plan.waypoints)
    if n < 2:
        raise MalformedMessageError(f"RoutePlan {plan.plan_id!r} has {n} waypoint(s), needs >= 2")
    for i, w in enumerate(plan.waypoints):
        if not _finite_position(w.lat_deg, w.lon_deg):
            raise MalformedMessageError(
                f"RoutePlan {plan.plan_id!r} waypoint {i}: position ({w.lat_deg}, {w.lon_deg}) "
                "is not a valid latitude/longitude")
        if not math.isfinite(w.time_s):
            raise MalformedMessageError(f"RoutePlan {plan.plan_id!r} waypoint {i}: time missing")
    times = [w.time_s for w in plan.waypoints]
    if any(b < a for a, b in pairwise(times)):
        raise MalformedMessageError(f"RoutePlan {plan.plan_id!r}: waypoint times go backwards")
    if not plan.plan_id:
        raise MalformedMessageError("RoutePlan without plan_id")
    return plan


def check_fix(fix: ShipFix) -> ShipFix:
    """The fix itself when it has a usable position and time; MalformedMessageError otherwise."""
    if not (_finite_position(fix.lat_deg, fix.lon_deg) and abs(fix.lon_deg) <= 180.0):
        raise MalformedMessageError(
            f"ShipState position ({fix.lat_deg}, {fix.lon_deg}) is not a valid latitude/longitude")
    if not math.isfinite(fix.time_s) or fix.time_s <= 0:
        raise MalformedMessageError(f"ShipState time {fix.time_s} is missing")
    return fix


def check_profile(profile: Profile) -> Profile:
    """The profile itself when its stages are finite and ordered."""
    for i, s in enumerate(profile.stages):
        if not (math.isfinite(s.start_s) and math.isfinite(s.duration_s) and s.duration_s >= 0):
            raise MalformedMessageError(f"RpmProfile {profile.plan_id!r} stage {i}: start "
                                        f"{s.start_s} / duration {s.duration_s} s unusable")
    starts = [s.start_s for s in profile.stages]
    if any(b < a for a, b in pairwise(starts)):
        raise MalformedMessageError(f"RpmProfile {profile.plan_id!r}: stage starts go backwards")
    return profile
