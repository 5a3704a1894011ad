"""Geodesy on the WGS 84 ellipsoid (pyproj.Geod) in a continuous longitude frame.

Routes are kept in an unwrapped longitude frame (e.g. Busan 129 E -> Long Beach 241.7 E) so
that crossing the antimeridian is not a discontinuity; `wrap_lon` maps back to -180..180.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike
from pyproj import Geod

from .units import M_PER_NM

GEOD = Geod(ellps="WGS84")
EARTH_MEAN_RADIUS_M = 6_371_008.8  # IUGG mean radius R1 = (2a + b) / 3 of WGS 84
__all__ = ["EARTH_MEAN_RADIUS_M", "GEOD", "M_PER_NM", "bearing_deg", "cross_track_m",
           "densify_track", "destination", "direct", "distance_m", "distance_within_m",
           "great_circle_points", "inverse", "spherical_m", "track_length_m", "unwrap_near",
           "wrap_lon"]


def wrap_lon(lon_deg: ArrayLike) -> np.ndarray:
    """Longitudes in -180..180."""
    return (np.asarray(lon_deg, dtype=float) + 180.0) % 360.0 - 180.0


def unwrap_near(lon_deg: ArrayLike, ref_deg: ArrayLike) -> np.ndarray:
    """Longitudes shifted by multiples of 360 to lie within 180 degrees of `ref_deg`."""
    lon = np.asarray(lon_deg, dtype=float)
    ref = np.asarray(ref_deg, dtype=float)
    return ref + (lon - ref + 180.0) % 360.0 - 180.0


def direct(lon_deg: ArrayLike, lat_deg: ArrayLike, azimuth_deg: ArrayLike,
           distance_m: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Geodesic direct problem; returned longitudes continue the input frame."""
    lon0 = np.asarray(lon_deg, dtype=float)
    lon, lat, _ = GEOD.fwd(
        wrap_lon(lon0), np.asarray(lat_deg, dtype=float), azimuth_deg, distance_m
    )
    return unwrap_near(lon, lon0), np.asarray(lat)


def inverse(lon0_deg: ArrayLike, lat0_deg: ArrayLike, lon1_deg: ArrayLike,
            lat1_deg: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Forward azimuth [deg] and distance [m] from point 0 to point 1."""
    az, _, dist = GEOD.inv(
        wrap_lon(lon0_deg), np.asarray(lat0_deg, dtype=float),
        wrap_lon(lon1_deg), np.asarray(lat1_deg, dtype=float),
    )
    return np.asarray(az) % 360.0, np.asarray(dist)


def great_circle_points(lon0: float, lat0: float, lon1: float, lat1: float,
                        n: int) -> tuple[np.ndarray, np.ndarray]:
    """`n` >= 2 points from point 0 to point 1 along the geodesic, both ends included."""
    az, dist = inverse(lon0, lat0, lon1, lat1)
    frac = np.linspace(0.0, 1.0, n)
    lon, lat = direct(np.full(n, lon0), np.full(n, lat0), np.full(n, az), dist * frac)
    return np.unwrap(lon, period=360.0), lat


def densify_track(lon_deg: ArrayLike, lat_deg: ArrayLike,
                  step_m: float) -> tuple[np.ndarray, np.ndarray]:
    """Points along each geodesic leg of a track, at most `step_m` apart."""
    lon = np.asarray(lon_deg, dtype=float)
    lat = np.asarray(lat_deg, dtype=float)
    out_lon, out_lat = [lon[:1]], [lat[:1]]
    az, dist = inverse(lon[:-1], lat[:-1], lon[1:], lat[1:])
    n = np.maximum(1, np.ceil(dist / step_m).astype(int))
    idx = np.repeat(np.arange(lon.size - 1), n)
    first = np.concatenate([[0], np.cumsum(n)[:-1]])
    frac = (np.arange(idx.size) - first[idx] + 1) / n[idx]
    plon, plat = direct(lon[idx], lat[idx], az[idx], dist[idx] * frac)
    out_lon.append(plon)
    out_lat.append(plat)
    return np.concatenate(out_lon), np.concatenate(out_lat)


def distance_m(lon0_deg: ArrayLike, lat0_deg: ArrayLike, lon1_deg: ArrayLike,
               lat1_deg: ArrayLike) -> np.ndarray:
    """Geodesic distance [m] from point 0 to point 1 on WGS 84, broadcast over arrays."""
    return inverse(lon0_deg, lat0_deg, lon1_deg, lat1_deg)[1]


# largest relative gap between the WGS 84 geodesic and the great circle on the mean sphere
# (under 0.6 %: the ellipsoid's flattening is 1/298), with room to spare
SPHERE_GAP = 0.01


def spherical_m(lon_deg: ArrayLike, lat_deg: ArrayLike, to_lon_deg: float,
                to_lat_deg: float) -> np.ndarray:
    """Great-circle distances [m] on the mean-radius sphere (haversine): within SPHERE_GAP
    of the WGS 84 geodesic, at a fraction of its cost."""
    lon, lat = np.radians(lon_deg), np.radians(lat_deg)
    lon0, lat0 = np.radians(to_lon_deg), np.radians(to_lat_deg)
    h = (np.sin((lat - lat0) / 2.0) ** 2
         + np.cos(lat) * np.cos(lat0) * np.sin((lon - lon0) / 2.0) ** 2)
    return 2.0 * EARTH_MEAN_RADIUS_M * np.arcsin(np.sqrt(np.clip(h, 0.0, 1.0)))


def distance_within_m(lon_deg: ArrayLike, lat_deg: ArrayLike, lon1_deg: float, lat1_deg: float,
                      within_m: float) -> np.ndarray:
    """Distance [m] from points to one point: the WGS 84 geodesic wherever it may be within
    `within_m`, the great circle on the mean sphere (then surely beyond `within_m`) elsewhere.
    A threshold test over a grid costs a haversine instead of a geodesic per cell."""
    lon, lat = np.broadcast_arrays(np.asarray(lon_deg, dtype=float),
                                   np.asarray(lat_deg, dtype=float))
    shape = lon.shape
    lon, lat = lon.ravel(), lat.ravel()
    out = spherical_m(lon, lat, lon1_deg, lat1_deg)
    near = out <= within_m * (1.0 + SPHERE_GAP) + 1.0
    if near.any():
        out[near] = inverse(lon[near], lat[near], np.full(int(near.sum()), lon1_deg),
                            np.full(int(near.sum()), lat1_deg))[1]
    return out.reshape(shape)


def bearing_deg(lon0_deg: ArrayLike, lat0_deg: ArrayLike, lon1_deg: ArrayLike,
                lat1_deg: ArrayLike) -> np.ndarray:
    """Initial geodesic bearing [deg true, 0..360) from point 0 towards point 1."""
    return inverse(lon0_deg, lat0_deg, lon1_deg, lat1_deg)[0]


def destination(lon_deg: ArrayLike, lat_deg: ArrayLike, bearing: ArrayLike,
                dist_m: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Point (lon in -180..180, lat) reached after `dist_m` along the geodesic of `bearing`."""
    lon, lat = direct(lon_deg, lat_deg, bearing, dist_m)
    return wrap_lon(lon), lat


def cross_track_m(lon_deg: ArrayLike, lat_deg: ArrayLike, a_lon: float, a_lat: float,
                  b_lon: float, b_lat: float) -> np.ndarray:
    """Signed distance [m, + to the right] of points from the great circle A -> B: the
    spherical cross-track formula on the mean radius, fed with WGS 84 azimuths and distances."""
    az_ab, _ = inverse(a_lon, a_lat, b_lon, b_lat)
    shape = np.shape(lon_deg)
    az_ap, d_ap = inverse(np.full(shape, a_lon), np.full(shape, a_lat), lon_deg, lat_deg)
    delta = d_ap / EARTH_MEAN_RADIUS_M
    return np.asarray(EARTH_MEAN_RADIUS_M * np.arcsin(
        np.sin(delta) * np.sin(np.radians(az_ap - az_ab))))


def track_length_m(lon_deg: ArrayLike, lat_deg: ArrayLike) -> float:
    """Total geodesic length [m] of a polyline track."""
    lon = np.asarray(lon_deg, dtype=float)
    lat = np.asarray(lat_deg, dtype=float)
    _, d = inverse(lon[:-1], lat[:-1], lon[1:], lat[1:])
    return float(np.sum(d))
