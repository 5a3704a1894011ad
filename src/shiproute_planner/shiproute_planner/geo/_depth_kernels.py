"""Numba kernels: water depth at points and the shallowest sample along great-circle legs."""

from __future__ import annotations

import math

import numba
import numpy as np

from .land_kernels import chord_sample, segment_ends

# columns of the grid table (one row per grid, finest first)
LAT0, DLAT, LON0, DLON, N_LAT, N_LON, PERIODIC, OFFSET = range(8)


@numba.njit(cache=True, nogil=True)
def depth_at(lat: float, lon: float, data: np.ndarray, grids: np.ndarray) -> float:
    """Depth [m] of the nearest cell centre in the finest grid that has a value there."""
    for g in range(grids.shape[0]):
        dlat = grids[g, DLAT]
        i = int(math.floor((lat - grids[g, LAT0]) / dlat + 0.5))  # noqa: RUF046 - numba
        if i < 0 or i >= int(grids[g, N_LAT]):
            continue
        dlon = grids[g, DLON]
        n_lon = int(grids[g, N_LON])
        dl = (lon - grids[g, LON0] + 0.5 * dlon) % 360.0 - 0.5 * dlon
        j = int(math.floor(dl / dlon + 0.5))  # noqa: RUF046 - numba
        if grids[g, PERIODIC] > 0.5:
            j = j % n_lon
        elif j < 0 or j >= n_lon:
            continue
        v = data[int(grids[g, OFFSET]) + i * n_lon + j]
        if not math.isnan(v):
            return v
    return math.nan


@numba.njit(cache=True, nogil=True)
def depths_at(lat: np.ndarray, lon: np.ndarray, data: np.ndarray, grids: np.ndarray,
              out: np.ndarray) -> None:
    """`depth_at` for arrays of points."""
    for k in range(lat.size):
        out[k] = depth_at(lat[k], lon[k], data, grids)


@numba.njit(cache=True, nogil=True)
def _finest_cell_deg(lat0: float, lon0: float, lat1: float, lon1: float,
                     grids: np.ndarray) -> float:
    """Cell size [deg] of the finest grid whose box meets the segment's (padded) box."""
    lo_lat, hi_lat = min(lat0, lat1) - 0.5, max(lat0, lat1) + 0.5
    for g in range(grids.shape[0]):  # finest first: the first that meets wins
        g_lo = grids[g, LAT0] - 0.5 * grids[g, DLAT]
        g_hi = g_lo + grids[g, N_LAT] * grids[g, DLAT]
        if hi_lat < g_lo or lo_lat > g_hi:
            continue
        if grids[g, PERIODIC] > 0.5:
            return max(grids[g, DLAT], grids[g, DLON])
        width = grids[g, N_LON] * grids[g, DLON]
        west = grids[g, LON0] - 0.5 * grids[g, DLON]
        a = (min(lon0, lon1) - 0.5 - west) % 360.0
        span = abs(lon1 - lon0) + 1.0
        if a <= width or a + span >= 360.0:
            return max(grids[g, DLAT], grids[g, DLON])
    return math.nan


@numba.njit(cache=True, nogil=True)
def segment_min_depth(lon0: np.ndarray, lat0: np.ndarray, lon1: np.ndarray,
                      lat1: np.ndarray, cap_m: np.ndarray, data: np.ndarray,
                      grids: np.ndarray, coarse: np.ndarray, block_deg: float,
                      out: np.ndarray) -> None:
    """Shallowest depth [m] along each great-circle segment, capped at `cap_m`.

    Samples lie on the segment at an eighth of the finest overlapping grid's spacing. `coarse` is a
    global raster (row 0 at 90 S, column 0 at 180 W) of the minimum known depth within one
    block of each block (+inf where unknown); where it is at least the cap the walk jumps
    most of a block ahead, so deep-ocean legs cost a few lookups. NaN: no grid covers the
    segment (depth unknown).
    """
    n_blat, n_blon = coarse.shape
    for s in range(lon0.size):
        cell = _finest_cell_deg(lat0[s], lon0[s], lat1[s], lon1[s], grids)
        if math.isnan(cell):
            out[s] = math.nan
            continue
        ax, ay, az, bx, by, bz, arc = segment_ends(lat0[s], lon0[s], lat1[s], lon1[s])
        # an eighth of a cell: a leg that cuts a cell's corner crosses it for less than half
        # a cell, and at half-cell steps a shoal's corner could fall between two samples
        n = max(1, int(math.ceil(arc / (0.125 * cell))))  # noqa: RUF046 - numba
        step = arc / n
        cap = cap_m[s]
        best = math.inf
        seen = False
        k = 0
        while k <= n:
            lat, lon = chord_sample(ax, ay, az, bx, by, bz, k / n)
            bi = min(max(int((lat + 90.0) / block_deg), 0), n_blat - 1)
            bj = min(max(int(((lon + 180.0) % 360.0) / block_deg), 0), n_blon - 1)
            if coarse[bi, bj] >= cap:
                if coarse[bi, bj] < math.inf:
                    seen = True  # known to be at least the cap here
                # the block value covers the block and its neighbours: jump 0.95 block in
                # latitude, in longitude shrunk by the cosine of the most poleward latitude
                # one block on (a jump in arc would leave the neighbourhood towards the poles)
                c = math.cos(math.radians(min(abs(lat) + block_deg, 89.0)))
                skip = max(1, int(0.95 * block_deg * c / max(step, 1e-12)))
                k += skip if k + skip <= n or k == n else n - k
                continue
            v = depth_at(lat, lon, data, grids)
            if not math.isnan(v):
                seen = True
                if v < best:
                    best = v
            k += 1
        if best < cap:
            out[s] = best
        else:
            out[s] = cap if seen else math.nan
