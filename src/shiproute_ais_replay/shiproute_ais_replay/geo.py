"""Spherical-earth geodesy on arrays: great-circle distance, initial bearing, destination."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

EARTH_RADIUS_M = 6_371_008.8  # IUGG mean radius
M_PER_NM = 1852.0
M_S_PER_KN = M_PER_NM / 3600.0


def distance_m(lat1_deg: ArrayLike, lon1_deg: ArrayLike, lat2_deg: ArrayLike,
               lon2_deg: ArrayLike) -> np.ndarray:
    """Great-circle (haversine) distance [m] between points, broadcast over arrays."""
    p1, p2 = np.radians(lat1_deg), np.radians(lat2_deg)
    dl = np.radians(np.asarray(lon2_deg, float) - np.asarray(lon1_deg, float))
    a = np.sin((p2 - p1) / 2) ** 2 + np.cos(p1) * np.cos(p2) * np.sin(dl / 2) ** 2
    return 2 * EARTH_RADIUS_M * np.arcsin(np.sqrt(np.clip(a, 0.0, 1.0)))


def bearing_deg(lat1_deg: ArrayLike, lon1_deg: ArrayLike, lat2_deg: ArrayLike,
                lon2_deg: ArrayLike) -> np.ndarray:
    """Initial great-circle bearing [deg true, 0..360) from point 1 towards point 2."""
    p1, p2 = np.radians(lat1_deg), np.radians(lat2_deg)
    dl = np.radians(np.asarray(lon2_deg, float) - np.asarray(lon1_deg, float))
    y = np.sin(dl) * np.cos(p2)
    x = np.cos(p1) * np.sin(p2) - np.sin(p1) * np.cos(p2) * np.cos(dl)
    return np.degrees(np.arctan2(y, x)) % 360.0


def destination(lat_deg: ArrayLike, lon_deg: ArrayLike, bearing: ArrayLike,
                dist_m: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Point reached after ``dist_m`` along great circle with initial ``bearing`` [deg]."""
    p1, l1 = np.radians(lat_deg), np.radians(lon_deg)
    th, d = np.radians(bearing), np.asarray(dist_m, float) / EARTH_RADIUS_M
    p2 = np.arcsin(np.sin(p1) * np.cos(d) + np.cos(p1) * np.sin(d) * np.cos(th))
    l2 = l1 + np.arctan2(np.sin(th) * np.sin(d) * np.cos(p1), np.cos(d) - np.sin(p1) * np.sin(p2))
    return np.degrees(p2), (np.degrees(l2) + 180.0) % 360.0 - 180.0


def wrap_lon_deg(lon_deg: ArrayLike) -> np.ndarray:
    """Longitude wrapped into [-180, 180)."""
    return (np.asarray(lon_deg, float) + 180.0) % 360.0 - 180.0
