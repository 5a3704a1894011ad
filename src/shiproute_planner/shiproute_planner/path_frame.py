"""Poses of a planned track in the REP 105 ``earth`` frame (ECEF, WGS 84), and back.

``nav_msgs/Path`` carries metric poses, so a lat/lon track is written in the ``earth`` frame of
REP 105: x, y, z are WGS 84 Earth-centred, Earth-fixed metres (float64, so latitude/longitude
come back to well under a millimetre). Orientation is the ship's heading: REP 103 yaw
(counter-clockwise from local East, i.e. ENU) expressed as a rotation from the ECEF axes.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from pyproj import Transformer
from scipy.spatial.transform import Rotation

_TO_ECEF = Transformer.from_crs("EPSG:4979", "EPSG:4978", always_xy=True)
_FROM_ECEF = Transformer.from_crs("EPSG:4978", "EPSG:4979", always_xy=True)


@dataclass(frozen=True)
class EcefPoses:
    """Positions [m] and unit quaternions (x, y, z, w) of a track in the ECEF frame."""

    x_m: np.ndarray
    y_m: np.ndarray
    z_m: np.ndarray
    quaternion_xyzw: np.ndarray  # shape (n, 4)


def enu_axes(lat_deg: np.ndarray, lon_deg: np.ndarray) -> np.ndarray:
    """Local East, North, Up unit vectors in ECEF as columns of (n, 3, 3) matrices."""
    lat = np.radians(np.asarray(lat_deg, dtype=float))
    lon = np.radians(np.asarray(lon_deg, dtype=float))
    east = np.stack([-np.sin(lon), np.cos(lon), np.zeros_like(lon)], axis=-1)
    north = np.stack(
        [-np.sin(lat) * np.cos(lon), -np.sin(lat) * np.sin(lon), np.cos(lat)], axis=-1
    )
    up = np.stack([np.cos(lat) * np.cos(lon), np.cos(lat) * np.sin(lon), np.sin(lat)], axis=-1)
    return np.stack([east, north, up], axis=-1)


def track_to_ecef(lat_deg, lon_deg, heading_deg) -> EcefPoses:
    """Positions and heading orientations of a track (heading: deg true, going to) in ECEF."""
    lat = np.atleast_1d(np.asarray(lat_deg, dtype=float))
    lon = np.atleast_1d(np.asarray(lon_deg, dtype=float))
    heading = np.nan_to_num(np.atleast_1d(np.asarray(heading_deg, dtype=float)))
    x, y, z = _TO_ECEF.transform(lon, lat, np.zeros_like(lat))
    yaw = np.radians(90.0 - heading)  # REP 103: ENU yaw, counter-clockwise from East
    c, s = np.cos(yaw), np.sin(yaw)
    rot_yaw = np.zeros((lat.size, 3, 3))
    rot_yaw[:, 0, 0], rot_yaw[:, 0, 1], rot_yaw[:, 1, 0], rot_yaw[:, 1, 1] = c, -s, s, c
    rot_yaw[:, 2, 2] = 1.0
    rot = enu_axes(lat, lon) @ rot_yaw
    quaternions = Rotation.from_matrix(rot).as_quat()  # (x, y, z, w)
    return EcefPoses(np.asarray(x), np.asarray(y), np.asarray(z), quaternions)


def ecef_to_lat_lon(x_m, y_m, z_m) -> tuple[np.ndarray, np.ndarray]:
    """Recover WGS 84 latitude and longitude [deg] from ECEF positions [m]."""
    lon, lat, _ = _FROM_ECEF.transform(
        np.asarray(x_m, dtype=float), np.asarray(y_m, dtype=float), np.asarray(z_m, dtype=float)
    )
    return np.asarray(lat), np.asarray(lon)


def heading_from_quaternion(lat_deg, lon_deg, quaternion_xyzw: np.ndarray) -> np.ndarray:
    """Recover heading [deg true, going to] from ECEF orientations written by track_to_ecef."""
    q = np.atleast_2d(np.asarray(quaternion_xyzw, dtype=float))
    x, y, z, w = q[:, 0], q[:, 1], q[:, 2], q[:, 3]
    forward = np.stack(
        [1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)], axis=-1
    )  # the body x axis (bow) in ECEF
    axes = enu_axes(np.atleast_1d(lat_deg), np.atleast_1d(lon_deg))
    east = np.einsum("ni,ni->n", forward, axes[:, :, 0])
    north = np.einsum("ni,ni->n", forward, axes[:, :, 1])
    return np.degrees(np.arctan2(east, north)) % 360.0
