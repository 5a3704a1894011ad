"""Frozen plan values: `Waypoint` per node (leg values start there) and `RoutePlan`.

Field names and units mirror shiproute_msgs/RouteWaypoint and RoutePlan so `convert.py` can
copy them one to one; times are POSIX seconds (UTC), longitudes -180..180 on output.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from shiproute_core.flags import describe_flags
from shiproute_core.geodesy import wrap_lon
from shiproute_core.units import M_PER_NM, M_S_PER_KNOT

from .route.evaluation import RouteEvaluation


@dataclass(frozen=True)
class Waypoint:
    """A node of a plan and the leg that starts there (leg values NaN on the last node)."""

    lat_deg: float
    lon_deg: float
    time_s: float
    heading_deg: float
    shaft_rpm: float
    stw_kn: float
    sog_kn: float
    leg_distance_nm: float
    leg_duration_s: float
    leg_fuel_t: float
    brake_power_kw: float
    hs_m: float
    wave_from_deg: float
    wind_speed_m_s: float
    wind_from_deg: float
    p_slamming: float
    p_deck_wetness: float
    p_propeller_emergence: float
    constraint_flags: int
    port: str = ""  # port name at departure/arrival/via nodes
    # shallowest charted depth on the leg and the under-keel clearance left there after
    # draft, squat, wave allowance and margin (NaN: depth not checked)
    min_depth_m: float = float("nan")
    ukc_m: float = float("nan")


@dataclass(frozen=True)
class RoutePlan:
    """A complete voyage plan (all legs of a multi-port voyage joined)."""

    plan_id: str
    method: str
    seed_source: str
    objective: str
    ship_name: str
    cycle_id: str
    departure_s: float
    rta_s: float
    eta_s: float
    feasible: bool
    infeasible_reasons: tuple[str, ...]
    total_fuel_t: float
    total_distance_nm: float
    total_time_s: float
    baseline_fuel_t: float
    baseline_method: str
    baseline_distance_nm: float
    baseline_eta_s: float
    baseline_feasible: bool
    baseline_rpm: float
    compute_time_s: float
    waypoints: tuple[Waypoint, ...]
    ports: tuple[str, ...]
    stage_s: float
    generations: int
    evaluations: int
    vessel_max_wave_m: float
    vessel_max_wind_m_s: float
    baseline_track: tuple[tuple[float, float], ...] = ()  # (lat, lon) of the baseline nodes
    leg_rtas_s: tuple[float, ...] = ()
    # waypoint index ranges (first, last) planned by the method; the rest are port approaches
    optimised_spans: tuple[tuple[int, int], ...] = ()
    # what the plan was made without, estimated or did not check, in words (never silent)
    warnings: tuple[str, ...] = ()
    extra: dict = field(default_factory=dict, compare=False)
    # ensemble forecasts (`ensemble_report`): members the plan was sailed on (0: one forecast),
    # the risk measure that chose it ("" = planned on the members' mean), P10/P50/P90 of fuel
    # [t] and ETA [POSIX s] over the members, the probability (member weight) of meeting Hs
    # above the ship's limit and of arriving late, and per leg the members' (min, median, max)
    # of Hs [m] and wind speed [m/s] (NaN on legs not sailed on the members)
    ensemble_members: int = 0
    risk_measure: str = ""
    fuel_quantiles_t: tuple[float, ...] = ()
    eta_quantiles_s: tuple[float, ...] = ()
    p_hs_violation: float = float("nan")
    p_late: float = float("nan")
    leg_hs_spread_m: tuple[tuple[float, float, float], ...] = ()
    leg_wind_spread_m_s: tuple[tuple[float, float, float], ...] = ()

    @property
    def fuel_saving_t(self) -> float:
        """Baseline fuel minus plan fuel [t] (positive = the plan saves fuel)."""
        return self.baseline_fuel_t - self.total_fuel_t

    @property
    def fuel_saving_pct(self) -> float:
        """Fuel saving relative to the baseline [%]."""
        return 100.0 * self.fuel_saving_t / self.baseline_fuel_t if self.baseline_fuel_t else 0.0

    def track(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Continuous-longitude node arrays (lon, lat, time_s)."""
        lon = np.unwrap(np.array([w.lon_deg for w in self.waypoints]), period=360.0)
        lat = np.array([w.lat_deg for w in self.waypoints])
        t = np.array([w.time_s for w in self.waypoints])
        return lon, lat, t

    def optimised_tracks(self) -> list[tuple[np.ndarray, np.ndarray]]:
        """(lon, lat) of each method-planned span, without the port approaches."""
        lon, lat, _ = self.track()
        spans = self.optimised_spans or ((0, len(self.waypoints) - 1),)
        return [(lon[a:b + 1], lat[a:b + 1]) for a, b in spans]

    def leg_rpm(self) -> np.ndarray:
        """RPM per leg (one fewer than waypoints)."""
        return np.array([w.shaft_rpm for w in self.waypoints[:-1]])


def _dir_from(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Meteorological 'coming from' direction of a (u, v) vector [deg]."""
    return np.degrees(np.arctan2(-u, -v)) % 360.0


def waypoints_from_evaluation(ev: RouteEvaluation, weather: dict, port_names: dict[int, str]
                              ) -> list[Waypoint]:
    """Waypoints of the single route in `ev` (index 0); `weather` sampled at leg starts."""
    legs = {k: np.asarray(v[0], dtype=float) for k, v in ev.legs.items()}
    m = legs["rpm"].size
    nan = float("nan")
    wave_from = weather.get("sea_surface_wave_from_direction", np.full(m, nan))
    u = weather.get("eastward_wind", np.full(m, nan))
    v = weather.get("northward_wind", np.full(m, nan))
    wind_from = _dir_from(np.asarray(u), np.asarray(v))
    out = []
    for k in range(m + 1):
        leg = k < m
        def g(name: str, kk: int = k, is_leg: bool = leg) -> float:
            return float(legs[name][kk]) if is_leg else nan
        out.append(Waypoint(
            lat_deg=float(ev.lat_deg[0, k]), lon_deg=float(wrap_lon(ev.lon_deg[0, k])),
            time_s=float(ev.time_s[0, k]), heading_deg=g("heading_deg"), shaft_rpm=g("rpm"),
            stw_kn=g("stw_m_s") / M_S_PER_KNOT, sog_kn=g("sog_m_s") / M_S_PER_KNOT,
            leg_distance_nm=g("distance_m") / M_PER_NM, leg_duration_s=g("duration_s"),
            leg_fuel_t=g("fuel_t"), brake_power_kw=g("brake_power_kw"), hs_m=g("hs_m"),
            wave_from_deg=float(wave_from[k]) if leg else nan,
            wind_speed_m_s=g("wind_speed_m_s"),
            wind_from_deg=float(wind_from[k]) if leg else nan,
            p_slamming=g("p_slamming"), p_deck_wetness=g("p_deck_wetness"),
            p_propeller_emergence=g("p_propeller_emergence"),
            constraint_flags=int(ev.leg_flags[0, k]) if leg else 0,
            port=port_names.get(k, ""),
            min_depth_m=g("min_depth_m") if "min_depth_m" in legs else nan,
            ukc_m=g("ukc_m") if "ukc_m" in legs else nan,
        ))
    return out


def reasons_of(flags: int) -> tuple[str, ...]:
    """Infeasibility reasons of a route flag mask."""
    return tuple(describe_flags(int(flags)))
