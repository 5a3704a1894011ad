"""Numba kernels: sample great-circle segments against the land raster."""

from __future__ import annotations

import math

import numba
import numpy as np

FINE = 3  # refinement of the sample step inside coastal cells
_D2R = math.pi / 180.0


@numba.njit(cache=True, nogil=True)
def segment_ends(lat0_deg: float, lon0_deg: float, lat1_deg: float, lon1_deg: float):
    """Unit vectors of a segment's ends and its great-circle arc [deg]."""
    la0, lo0, la1, lo1 = lat0_deg * _D2R, lon0_deg * _D2R, lat1_deg * _D2R, lon1_deg * _D2R
    ax, ay, az = math.cos(la0) * math.cos(lo0), math.cos(la0) * math.sin(lo0), math.sin(la0)
    bx, by, bz = math.cos(la1) * math.cos(lo1), math.cos(la1) * math.sin(lo1), math.sin(la1)
    dot = min(1.0, max(-1.0, ax * bx + ay * by + az * bz))
    return ax, ay, az, bx, by, bz, math.acos(dot) / _D2R


@numba.njit(cache=True, nogil=True)
def chord_sample(ax: float, ay: float, az: float, bx: float, by: float, bz: float, f: float):
    """Latitude and longitude [deg] of the point at fraction f along the chord A->B, projected
    back onto the sphere (the samples of a great-circle segment)."""
    x = ax + f * (bx - ax)
    y = ay + f * (by - ay)
    z = az + f * (bz - az)
    r = math.sqrt(x * x + y * y + z * z)
    return math.asin(z / r) / _D2R, math.atan2(y, x) / _D2R


@numba.njit(cache=True, nogil=True)
def scan_segments(
    lon0: np.ndarray,
    lat0: np.ndarray,
    lon1: np.ndarray,
    lat1: np.ndarray,
    raster: np.ndarray,
    cell_deg: float,
    spacing_deg: float,
    land_count: np.ndarray,
    coast_lon: np.ndarray,
    coast_lat: np.ndarray,
    coast_seg: np.ndarray,
) -> int:
    """Count raster-land samples per segment; list samples in coastal cells.

    Samples lie on the great circle between the end points (normalised linear interpolation
    of unit vectors), at most `spacing_deg` of arc apart, both ends included; inside coastal
    cells the step is refined three-fold so narrow land is not stepped over. Coastal samples
    of segments already on land are skipped. Returns the number of coastal samples written,
    or -1 if the coastal buffers were too small.
    """
    n_lat, n_lon = raster.shape
    inv = 1.0 / cell_deg
    n_coast = 0
    cap = coast_lon.size
    for s in range(lon0.size):
        ax, ay, az, bx, by, bz, arc_deg = segment_ends(lat0[s], lon0[s], lat1[s], lon1[s])
        n = max(1, math.ceil(arc_deg / spacing_deg))
        count = 0
        k = 0
        sub = 0  # > 0 while refining inside a coastal stretch
        steps = FINE * n
        while k <= steps:
            lat, lon = chord_sample(ax, ay, az, bx, by, bz, k / steps)
            i = min(max(int((lat + 90.0) * inv), 0), n_lat - 1)
            j = min(max(int((lon + 180.0) * inv), 0), n_lon - 1)
            v = raster[i, j]
            if v == 1:
                count += 1
            elif v == 2:
                if sub == 0 and k > 0:
                    # entering a coastal cell: go back and walk the last stretch finely
                    sub = FINE
                    k = max(k - (FINE - 1), 0)
                    continue
                if count == 0:
                    if n_coast >= cap:
                        return -1
                    coast_lon[n_coast] = lon
                    coast_lat[n_coast] = lat
                    coast_seg[n_coast] = s
                    n_coast += 1
            if v == 2 or sub > 0:
                k += 1
                sub = max(sub - 1, 1) if v == 2 else sub - 1
            else:
                k += FINE
        land_count[s] = count
    return n_coast


@numba.njit(cache=True, nogil=True)
def raster_lookup(
    lon: np.ndarray, lat: np.ndarray, raster: np.ndarray, cell_deg: float
) -> np.ndarray:
    """Raster class (0 sea, 1 land, 2 coastal) at each point; any longitude frame."""
    n_lat, n_lon = raster.shape
    out = np.empty(lon.size, dtype=np.uint8)
    for k in range(lon.size):
        lo = (lon[k] + 180.0) % 360.0
        i = min(max(int((lat[k] + 90.0) / cell_deg), 0), n_lat - 1)
        j = min(max(int(lo / cell_deg), 0), n_lon - 1)
        out[k] = raster[i, j]
    return out
