"""Numba kernels: water depth at points and the shallowest sample along great-circle legs."""

from __future__ import annotations

import math

import numba
import numpy as np

from .angle_kernels import wrap360
from .land_kernels import chord_sample, segment_ends

# columns of the grid table (one row per grid, finest first)
LAT0, DLAT, LON0, DLON, N_LAT, N_LON, PERIODIC, OFFSET = range(8)
_D2R = math.pi / 180.0  # as land_kernels


@numba.njit(cache=True, nogil=True)
def unit_vector(lat_deg: float, lon_deg: float):
    """Unit vector of a point: `land_kernels.segment_ends`' arithmetic for one end (the
    same bits, tested), so a scan can reuse a shared end's."""
    la, lo = lat_deg * _D2R, lon_deg * _D2R
    return math.cos(la) * math.cos(lo), math.cos(la) * math.sin(lo), math.sin(la)


@numba.njit(cache=True, nogil=True)
def ends_arc_deg(ax: float, ay: float, az: float, bx: float, by: float, bz: float) -> float:
    """Great-circle arc [deg] between two unit vectors, as `land_kernels.segment_ends`."""
    dot = min(1.0, max(-1.0, ax * bx + ay * by + az * bz))
    return math.acos(dot) / _D2R


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
        dl = wrap360(lon - grids[g, LON0] + 0.5 * dlon) - 0.5 * dlon
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
        a = wrap360(min(lon0, lon1) - 0.5 - west)
        span = abs(lon1 - lon0) + 1.0
        if a <= width or a + span >= 360.0:
            return max(grids[g, DLAT], grids[g, DLON])
    return math.nan


@numba.njit(cache=True, nogil=True)
def _block_of(lat: float, lon: float, block_deg: float, n_rows: int, n_cols: int):
    """(row, column) of a global block raster (row 0 at 90 S, column 0 at 180 W)."""
    i = min(max(int((lat + 90.0) / block_deg), 0), n_rows - 1)
    j = min(max(int(wrap360(lon + 180.0) / block_deg), 0), n_cols - 1)
    return i, j


@numba.njit(cache=True, nogil=True)
def _block_samples(lat: float, block_deg: float, step: float) -> int:
    """Samples in 0.95 of a block, the longitude shrunk by the cosine of the most poleward
    latitude one block on (a jump in arc would leave the neighbourhood towards the poles)."""
    c = math.cos(math.radians(min(abs(lat) + block_deg, 89.0)))
    return max(1, int(0.95 * block_deg * c / max(step, 1e-12)))


@numba.njit(cache=True, nogil=True)
def _capped_minimum(best: float, cap: float, seen: bool) -> float:
    """A leg's answer: its minimum below the cap, the cap when only depths >= cap were
    known, NaN when no depth was."""
    if best < cap:
        return best
    return cap if seen else math.nan


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
            bi, bj = _block_of(lat, lon, block_deg, n_blat, n_blon)
            if coarse[bi, bj] >= cap:
                if coarse[bi, bj] < math.inf:
                    seen = True  # known to be at least the cap here
                # the block value covers the block and its neighbours
                skip = _block_samples(lat, block_deg, step)
                k += skip if k + skip <= n or k == n else n - k
                continue
            v = depth_at(lat, lon, data, grids)
            if not math.isnan(v):
                seen = True
                if v < best:
                    best = v
            k += 1
        out[s] = _capped_minimum(best, cap, seen)


@numba.njit(cache=True, nogil=True)
def segment_min_depth_skip(lon0: np.ndarray, lat0: np.ndarray, lon1: np.ndarray,
                           lat1: np.ndarray, cap_m: np.ndarray, data: np.ndarray,
                           grids: np.ndarray, coarse: np.ndarray, block_deg: float,
                           clear_deg: np.ndarray, clear_block_deg: float, threshold_m: float,
                           cell_min: np.ndarray, out: np.ndarray) -> None:
    """`segment_min_depth` with the same shallows for caps <= `threshold_m`, but open (or
    unknown) water crossed in long jumps: `clear_deg` holds, per block of `clear_block_deg`,
    a lower bound of the arc [deg] to the nearest `coarse` block known to be shallower than
    the threshold, so no sample closer than that is shallower than the cap (a jump over known
    water the plain walk would have met marks the leg `seen` only if it starts in it).
    With one grid, `cell_min` (its shape, uint8) holds the floor of the shallowest known
    depth [m] in each cell's 3 x 3 neighbourhood (255: none known, 254: 254 m or more); the
    shelf walk then jumps up to a cell where the neighbourhood is at least the cap deep (a
    (1, 1) array: no jumps). A dry sample (0 m) ends the leg's walk: nothing is shallower."""
    n_blat, n_blon = coarse.shape
    n_clat, n_clon = clear_deg.shape
    end_lat, end_lon, ex, ey, ez = math.nan, math.nan, 0.0, 0.0, 0.0  # last end's unit vector
    for s in range(lon0.size):
        cap = cap_m[s]
        if not cap <= threshold_m:  # NaN or above the raster's threshold: the plain walk
            segment_min_depth(lon0[s:s + 1], lat0[s:s + 1], lon1[s:s + 1], lat1[s:s + 1],
                              cap_m[s:s + 1], data, grids, coarse, block_deg, out[s:s + 1])
            continue
        cell = _finest_cell_deg(lat0[s], lon0[s], lat1[s], lon1[s], grids)
        if math.isnan(cell):
            out[s] = math.nan
            continue
        # a leg that starts where the last one ended (a route's next leg) reuses its unit
        # vector; zeros are recomputed (+0 and -0 compare equal but may differ in sign)
        if (lat0[s] == end_lat and lon0[s] == end_lon and end_lat != 0.0
                and end_lon != 0.0):
            ax, ay, az = ex, ey, ez
        else:
            ax, ay, az = unit_vector(lat0[s], lon0[s])
        bx, by, bz = unit_vector(lat1[s], lon1[s])
        end_lat, end_lon, ex, ey, ez = lat1[s], lon1[s], bx, by, bz
        arc = ends_arc_deg(ax, ay, az, bx, by, bz)
        n = max(1, int(math.ceil(arc / (0.125 * cell))))  # noqa: RUF046 - numba
        step = arc / n
        # the most arc one sample step covers: chord fractions run up to tan(h)/h faster
        # than arc fractions mid-leg (h: half the leg's arc); legs over 120 deg jump nothing
        half = math.radians(0.5 * arc)
        per_step = step * (math.tan(half) / half if half > 1e-9 else 1.0) if arc < 120.0 \
            else math.inf
        best = math.inf
        seen = False
        k = 0
        while k <= n:
            lat, lon = chord_sample(ax, ay, az, bx, by, bz, k / n)
            bi, bj = _block_of(lat, lon, block_deg, n_blat, n_blon)
            c = coarse[bi, bj]
            if c >= cap:
                if c < math.inf:
                    seen = True
                ci, cj = _block_of(lat, lon, clear_block_deg, n_clat, n_clon)
                jump = int(clear_deg[ci, cj] / max(per_step, 1e-12))
                if jump < 1:  # near shallows: the plain walk's block step
                    jump = _block_samples(lat, block_deg, step)
                k += jump if k + jump <= n or k == n else n - k
                continue
            v = depth_at(lat, lon, data, grids)
            if not math.isnan(v):
                seen = True
                if v < best:
                    best = v
                    if best <= 0.0:  # dry (grids read land as 0 m): nothing is shallower
                        break
            k += _cell_jump(lat, lon, cap, grids, cell_min, per_step, n - k)
        out[s] = _capped_minimum(best, cap, seen)


@numba.njit(cache=True, nogil=True)
def _cell_jump(lat: float, lon: float, cap: float, grids: np.ndarray, cell_min: np.ndarray,
               per_step: float, left: int) -> int:
    """Samples to move on from a shelf sample: 1, or (one grid, its cell's neighbourhood at
    least `cap` deep) as many as stay within one cell of the sample, hence inside the
    neighbourhood (never past the leg's last sample, always onto it)."""
    n_lat, n_lon = cell_min.shape
    if n_lat < 3 or left <= 1:
        return 1
    dlat, dlon = grids[0, DLAT], grids[0, DLON]
    i = int(math.floor((lat - grids[0, LAT0]) / dlat + 0.5))  # noqa: RUF046 - numba
    dl = wrap360(lon - grids[0, LON0] + 0.5 * dlon) - 0.5 * dlon
    j = int(math.floor(dl / dlon + 0.5))  # noqa: RUF046 - numba
    if grids[0, PERIODIC] > 0.5:
        j = j % n_lon
    elif j < 1 or j >= n_lon - 1:
        return 1
    if i < 1 or i >= n_lat - 1 or cell_min[i, j] < cap:
        return 1  # (unknown neighbourhoods, 255, are crossed: no sample there is shallow)
    c = math.cos(math.radians(min(abs(lat) + dlat, 89.0)))
    jump = int(0.95 * min(dlat, dlon * c) / max(per_step, 1e-12))
    return max(1, min(jump, left))
