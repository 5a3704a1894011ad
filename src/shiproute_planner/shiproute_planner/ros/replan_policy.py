"""When the ship has left its plan: cross-track and schedule deviation from the planned track.

The planned track is densified along its geodesic legs (one point per ``step_nm``) with the
planned time interpolated along each leg; the ship's nearest point gives the cross-track
distance and the schedule deviation (actual time minus planned time at that point).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from shiproute_core.geodesy import GEOD, inverse
from shiproute_core.units import M_PER_NM

from ..plan_types import RoutePlan


@dataclass(frozen=True)
class TrackDeviation:
    """How far the ship is from its plan, in space and in time."""

    cross_track_nm: float
    schedule_deviation_s: float  # > 0: behind schedule
    along_track_fraction: float  # 0 at departure, 1 at arrival


@dataclass(frozen=True)
class ReplanThresholds:
    """Limits beyond which the planner re-plans from the ship's current state."""

    cross_track_nm: float = 20.0
    schedule_s: float = 3.0 * 3600.0

    def exceeded(self, deviation: TrackDeviation) -> list[str]:
        """Reasons (empty when within limits)."""
        reasons = []
        if deviation.cross_track_nm > self.cross_track_nm:
            reasons.append(
                f"cross-track {deviation.cross_track_nm:.1f} NM > {self.cross_track_nm:.1f} NM"
            )
        if abs(deviation.schedule_deviation_s) > self.schedule_s:
            reasons.append(
                f"schedule off by {deviation.schedule_deviation_s / 3600:.1f} h"
                f" (limit {self.schedule_s / 3600:.1f} h)"
            )
        return reasons


def densify_track(
    lat_deg: np.ndarray, lon_deg: np.ndarray, time_s: np.ndarray, step_nm: float = 2.0
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Points along the geodesic legs of a track with linearly interpolated planned times."""
    lats, lons, times = [float(lat_deg[0])], [float(lon_deg[0])], [float(time_s[0])]
    for i in range(len(lat_deg) - 1):
        _, _, dist_m = GEOD.inv(lon_deg[i], lat_deg[i], lon_deg[i + 1], lat_deg[i + 1])
        n_inner = max(int(dist_m / (step_nm * M_PER_NM)), 0)
        if n_inner:
            pts = np.asarray(
                GEOD.npts(lon_deg[i], lat_deg[i], lon_deg[i + 1], lat_deg[i + 1], n_inner)
            )
            frac = np.arange(1, n_inner + 1) / (n_inner + 1)
            lons.extend(pts[:, 0])
            lats.extend(pts[:, 1])
            times.extend(time_s[i] + frac * (time_s[i + 1] - time_s[i]))
        lats.append(float(lat_deg[i + 1]))
        lons.append(float(lon_deg[i + 1]))
        times.append(float(time_s[i + 1]))
    return np.asarray(lats), np.asarray(lons), np.asarray(times)


def track_deviation(
    track_lat_deg: np.ndarray,
    track_lon_deg: np.ndarray,
    track_time_s: np.ndarray,
    ship_lat_deg: float,
    ship_lon_deg: float,
    ship_time_s: float,
    step_nm: float = 2.0,
) -> TrackDeviation:
    """Cross-track distance [NM] and schedule deviation [s] of the ship from a planned track."""
    lats, lons, times = densify_track(
        np.asarray(track_lat_deg, float), np.asarray(track_lon_deg, float),
        np.asarray(track_time_s, float), step_nm,
    )
    n = lats.size
    _, _, dist_m = GEOD.inv(
        np.full(n, ship_lon_deg), np.full(n, ship_lat_deg), lons, lats
    )
    k = int(np.argmin(dist_m))
    return TrackDeviation(
        cross_track_nm=float(dist_m[k] / M_PER_NM),
        schedule_deviation_s=float(ship_time_s - times[k]),
        along_track_fraction=k / max(n - 1, 1),
    )


def at_departure_port(origin: str, lat_deg: float, lon_deg: float, radius_nm: float) -> bool:
    """Whether a ship at (lat, lon) is still at the departure port `origin` (within
    `radius_nm` of it): its plan then starts at the port. An unknown origin means no."""
    from ..geo.landmask import default_land_mask
    from ..geo.ports import resolve_port

    try:
        port = resolve_port(origin, default_land_mask())
    except Exception:  # an unknown origin just means "plan from the ship"
        return False
    _, dist_m = inverse(port.lon_deg, port.lat_deg, lon_deg, lat_deg)
    return float(dist_m) / M_PER_NM <= radius_nm


def off_plan_reasons(plan: RoutePlan, position: tuple[float, float, float],
                     thresholds: ReplanThresholds) -> list[str]:
    """Why a ship at `position` (lat, lon, time) has left `plan` (empty while on it)."""
    lon, lat, t = plan.track()
    dev = track_deviation(lat, lon, t, position[0], position[1], position[2])
    return list(thresholds.exceeded(dev))
