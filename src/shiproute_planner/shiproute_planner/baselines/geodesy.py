"""Geodesic helpers of the baselines on top of the planner's `geo.geodesy` (continuous lon)."""

from __future__ import annotations

import numpy as np
from shiproute_core.geodesy import GEOD, M_PER_NM, densify_track, direct, inverse, unwrap_near

__all__ = [
    "EARTH_RADIUS_M",
    "GEOD",
    "M_PER_NM",
    "continuous_lon",
    "cross_track_m",
    "densify_track",
    "direct",
    "inverse",
    "track_length_m",
]

EARTH_RADIUS_M = 6_371_008.8


def continuous_lon(lon_deg: np.ndarray | float, ref_deg: float) -> np.ndarray:
    """Longitudes shifted by multiples of 360 deg to lie within 180 deg of `ref_deg`."""
    return unwrap_near(lon_deg, ref_deg)


def cross_track_m(
    lon_deg: np.ndarray, lat_deg: np.ndarray, a_lon: float, a_lat: float, b_lon: float, b_lat: float
) -> np.ndarray:
    """Signed distance (m, + to the right) of points from the great circle A -> B (spherical)."""
    az_ab, _ = inverse(a_lon, a_lat, b_lon, b_lat)
    shape = np.shape(lon_deg)
    az_ap, d_ap = inverse(np.full(shape, a_lon), np.full(shape, a_lat), lon_deg, lat_deg)
    delta = d_ap / EARTH_RADIUS_M
    return EARTH_RADIUS_M * np.arcsin(np.sin(delta) * np.sin(np.radians(az_ap - az_ab)))


def track_length_m(lon_deg: np.ndarray, lat_deg: np.ndarray) -> float:
    """Total geodesic length of a track."""
    _, d = inverse(lon_deg[:-1], lat_deg[:-1], lon_deg[1:], lat_deg[1:])
    return float(np.sum(d))
