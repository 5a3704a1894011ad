"""Whole-population route generation in one compiled call, and the GA's land verdict.

`generate_routes` runs the stage loop of `fast_eval` (weather sampling, sea state, ship model,
geodesic step; then the final connection steered at the port) inside numba, so a population
costs one Python call instead of four per stage. `ga_land_hits` is the GA loop's land test:
the exact scan's candidate samples, decided by the raster and, in coastal cells, by exact
verdicts on a ~1 km grid resolved on first use (`geo.fine_coast`).
"""

from __future__ import annotations

import math
import types
from typing import Any

import numpy as np
from numba import njit
from shiproute_weather.sampling.interp_kernel import trilinear as _trilinear_parallel

from ..geo.coast_distance import NM_PER_DEG, UNIT_NM
from ..geo.land_kernels import FINE, chord_sample, segment_ends
from . import _fast_kernels as fk
from .legs import MIN_SOG_M_S  # the exact evaluator's floor of the final connection's speed


def _serial_copy(fn: Any, name: str) -> Any:
    """`fn`'s Python function under another name: numba keys its on-disk cache by qualified
    name and source file, so a serial compilation of a parallel kernel needs its own name."""
    py = fn.py_func
    copy = types.FunctionType(py.__code__.replace(co_name=name, co_qualname=name), py.__globals__,
                              name, py.__defaults__, py.__closure__)
    copy.__qualname__ = name
    return copy


# the sampler's kernel compiled serially: populations run in chunks on Python threads, and
# numba's parallel launcher must not be entered from two threads at once
trilinear = njit(cache=True, nogil=True)(_serial_copy(_trilinear_parallel, "trilinear_serial"))


@njit(cache=True, nogil=True)
def _stage(lon, lat, t, rpm, hdg, has_wx, data, times_s, lat0, dlat, lon0, dlon, periodic,
           chan, isdir, limits, par, r_calm, wake, u_ws, u_sw, m0_ws, m0_sw, caa, sfoc_x,
           sfoc_y, wx, sea, f, b):
    """Ship model outputs f (11, P) and flags b (5, P) at the points for rpm/heading."""
    if has_wx:
        trilinear(data, times_s, lat0, dlat, lon0, dlon, periodic, lon, lat, t, wx)
        fk.fill_sea(wx, chan, isdir, sea, limits)
    else:
        sea[:] = 0.0
        sea[4] = 8.0
        sea[7] = 8.0
    fk.perform(rpm, hdg, sea, par, r_calm, wake, u_ws, u_sw, m0_ws, m0_sw, caa, sfoc_x, sfoc_y,
               f, b)


@njit(cache=True, nogil=True)
def generate_routes(headings, rpm, dep_lon, dep_lat, depart_s, stage_s, arr_lon, arr_lat,
                    rpm_lo, rpm_hi, has_wx, data, times_s, lat0, dlat, lon0, dlon, periodic,
                    chan, isdir, limits, par, r_calm, wake, u_ws, u_sw, m0_ws, m0_sw, caa,
                    sfoc_x, sfoc_y, lon, lat, t, out_f, out_b, heading_n, dist_n, dur_n):
    """Nodes (pop, n + 2) and leg outputs (11|5, pop, n + 1) of routes from stage headings
    (pop, n) [deg going to] and RPMs (pop, n + 1); see `fast_eval.FastEvaluator`."""
    pop, n = headings.shape
    nch = data.shape[3]
    wx = np.empty((nch, pop))
    sea = np.empty((10, pop))
    f = np.empty((11, pop))
    b = np.empty((5, pop), dtype=np.bool_)
    lo_i, la_i, t_i = np.empty(pop), np.empty(pop), np.empty(pop)
    r_i, h_i, d_i = np.empty(pop), np.empty(pop), np.empty(pop)
    nl, nt = np.empty(pop), np.empty(pop)
    for p in range(pop):
        lo_i[p], la_i[p], t_i[p] = dep_lon, dep_lat, depart_s
        lon[p, 0], lat[p, 0], t[p, 0] = dep_lon, dep_lat, depart_s
    for i in range(n):
        for p in range(pop):
            r_i[p] = min(max(rpm[p, i], rpm_lo), rpm_hi)
            h_i[p] = fk.wrap360(headings[p, i])
        _stage(lo_i, la_i, t_i, r_i, h_i, has_wx, data, times_s, lat0, dlat, lon0, dlon,
               periodic, chan, isdir, limits, par, r_calm, wake, u_ws, u_sw, m0_ws, m0_sw, caa,
               sfoc_x, sfoc_y, wx, sea, f, b)
        for p in range(pop):
            d_i[p] = max(f[1, p], 0.0) * stage_s
        fk.direct_many(lo_i, la_i, f[2], d_i, nl, nt)
        for p in range(pop):
            for k in range(11):
                out_f[k, p, i] = f[k, p]
            for k in range(5):
                out_b[k, p, i] = b[k, p]
            lo_i[p], la_i[p] = nl[p], nt[p]
            t_i[p] += stage_s
            lon[p, i + 1], lat[p, i + 1], t[p, i + 1] = nl[p], nt[p], t_i[p]
    # final connection: steer so that the course over ground points at the port
    a_lon, a_lat = np.full(pop, arr_lon), np.full(pop, arr_lat)
    course = np.empty(pop)
    fk.inverse_many(lo_i, la_i, a_lon, a_lat, course, dist_n)
    for p in range(pop):
        r_i[p] = min(max(rpm[p, n], rpm_lo), rpm_hi)
        h_i[p] = course[p]
    _stage(lo_i, la_i, t_i, r_i, h_i, has_wx, data, times_s, lat0, dlat, lon0, dlon, periodic,
           chan, isdir, limits, par, r_calm, wake, u_ws, u_sw, m0_ws, m0_sw, caa, sfoc_x,
           sfoc_y, wx, sea, f, b)
    redo = False
    for p in range(pop):
        drift = fk.wrap360(f[2, p] - course[p] + 180.0) - 180.0
        heading_n[p] = course[p]
        if abs(drift) > 1e-6:
            heading_n[p] = fk.wrap360(course[p] - drift)
            redo = True
    if redo:  # same sea state, corrected heading
        fk.perform(r_i, heading_n, sea, par, r_calm, wake, u_ws, u_sw, m0_ws, m0_sw, caa,
                   sfoc_x, sfoc_y, f, b)
    for p in range(pop):
        for k in range(11):
            out_f[k, p, n] = f[k, p]
        for k in range(5):
            out_b[k, p, n] = b[k, p]
        along = f[1, p] * math.cos(math.radians(f[2, p] - course[p]))
        dur_n[p] = dist_n[p] / max(along, MIN_SOG_M_S) if dist_n[p] > 0.0 else 0.0
        lon[p, n + 1], lat[p, n + 1] = arr_lon, arr_lat
        t[p, n + 1] = t_i[p] + dur_n[p]


@njit(cache=True, nogil=True)
def sail_stage(lon, lat, t, rpm, hdg, duration_s, has_wx, data, times_s, lat0, dlat, lon0, dlon,
               periodic, chan, isdir, limits, par, r_calm, wake, u_ws, u_sw, m0_ws, m0_sw, caa,
               sfoc_x, sfoc_y, sog, cog, end_lon, end_lat):
    """One leg from each point at `rpm` / heading `hdg` [deg going to] for `duration_s`: speed
    and course over ground and where the leg ends (the seeds' stage-by-stage search)."""
    n = lon.size
    wx = np.empty((data.shape[3], n))
    sea = np.empty((10, n))
    f = np.empty((11, n))
    b = np.empty((5, n), dtype=np.bool_)
    _stage(lon, lat, t, rpm, hdg, has_wx, data, times_s, lat0, dlat, lon0, dlon, periodic,
           chan, isdir, limits, par, r_calm, wake, u_ws, u_sw, m0_ws, m0_sw, caa, sfoc_x,
           sfoc_y, wx, sea, f, b)
    dist = np.empty(n)
    for p in range(n):
        sog[p], cog[p] = f[1, p], f[2, p]
        dist[p] = max(f[1, p], 0.0) * duration_s
    fk.direct_many(lon, lat, cog, dist, end_lon, end_lat)


@njit(cache=True, nogil=True)
def polyline_eta(track_lon, track_lat, rpm, depart_s, has_wx, data, times_s, lat0, dlat, lon0,
                 dlon, periodic, chan, isdir, limits, par, r_calm, wake, u_ws, u_sw, m0_ws,
                 m0_sw, caa, sfoc_x, sfoc_y, eta):
    """Arrival time along a polyline at each constant `rpm`, every leg steered (current set
    corrected once) so its course over ground points at the next vertex in the weather met at
    its start: `route.legs.sail_to` leg by leg, for the constant-RPM search."""
    n = rpm.size
    wx = np.empty((data.shape[3], n))
    sea = np.empty((10, n))
    f = np.empty((11, n))
    b = np.empty((5, n), dtype=np.bool_)
    lo, la, lo1, la1 = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    course, dist, hdg = np.empty(n), np.empty(n), np.empty(n)
    t = np.full(n, depart_s)
    for k in range(track_lon.size - 1):
        lo[:], la[:] = track_lon[k], track_lat[k]
        lo1[:], la1[:] = track_lon[k + 1], track_lat[k + 1]
        fk.inverse_many(lo, la, lo1, la1, course, dist)
        if dist[0] <= 0.0:
            continue
        _stage(lo, la, t, rpm, course, has_wx, data, times_s, lat0, dlat, lon0, dlon, periodic,
               chan, isdir, limits, par, r_calm, wake, u_ws, u_sw, m0_ws, m0_sw, caa, sfoc_x,
               sfoc_y, wx, sea, f, b)
        for p in range(n):
            hdg[p] = fk.wrap360(course[p] - (fk.wrap360(f[2, p] - course[p] + 180.0) - 180.0))
        fk.perform(rpm, hdg, sea, par, r_calm, wake, u_ws, u_sw, m0_ws, m0_sw, caa, sfoc_x,
                   sfoc_y, f, b)
        for p in range(n):
            along = f[1, p] * math.cos(math.radians(f[2, p] - course[p]))
            t[p] += dist[p] / max(along, MIN_SOG_M_S)
    eta[:] = t


_GRADE_STEP = 8 * FINE  # samples per step after a hit, except across land interiors


@njit(cache=True, nogil=True)
def max_arc_per_step(arc_deg: float, steps: int) -> float:
    """Upper bound of the arc [deg] between consecutive chord-fraction samples of a segment
    of `arc_deg` in `steps` steps: the projected chord runs fastest at its middle, tan(a)/a
    times the mean for half-arc a (1 % at 20 deg)."""
    half = min(0.5 * arc_deg * math.pi / 180.0, 1.4)
    ratio = math.tan(half) / half if half > 1e-9 else 1.0
    return max(arc_deg / steps * ratio * (1.0 + 1e-9), 1e-12)


@njit(cache=True, nogil=True)
def ga_land_hits(lon0, lat0, lon1, lat1, coarse, clear_deg, coarse_deg, raster, coast_dist,
                 cell_deg, spacing_deg, fine_keys, fine, missing, out):
    """Land samples per segment for the GA loop. A segment that met a coastal cell not yet
    resolved before its first land sample gets -1, to be scanned again once
    `geo.fine_coast.FineCoast.add` has resolved the cells written to `missing` (returns how
    many; when `missing` is full, later cells are left for the next scan).

    Candidate samples are every point the exact scan (`geo.land_kernels.scan_segments`) can
    visit: fractions k / steps of the chord with its refined step throughout. A sample counts
    in a land cell, and in a coastal cell when its fine cell is land (`fine` row of the cell
    in sorted `fine_keys`; see `geo.fine_coast`). Samples that provably lie in sea cells are
    skipped: by the coarse cell's clear distance before the first hit, and by the signed
    distance to the nearest coastal cell (`coast_dist`, 0.1 NM, `geo.coast_distance`). After
    the first hit every later sample in a land or coastal cell counts (a violation graded by
    the length on land): inland the walk jumps by the distance to the coast and counts the
    samples jumped over, so a leg across a continent costs a few lookups. The count depends
    only on the samples, not on the jumps taken or on which cells were resolved before."""
    n_lat, n_lon = raster.shape
    c_lat, c_lon = coarse.shape
    f = fine.shape[1]
    inv, c_inv = 1.0 / cell_deg, 1.0 / coarse_deg
    unit_deg = UNIT_NM / NM_PER_DEG  # stored distance unit -> arc [deg]
    n_miss = 0
    for s in range(lon0.size):
        ax, ay, az, bx, by, bz, arc = segment_ends(lat0[s], lon0[s], lat1[s], lon1[s])
        steps = FINE * max(1, math.ceil(arc / spacing_deg))
        per_step = max_arc_per_step(arc, steps)  # samples within D of one: D / per_step
        count = 0
        unresolved = False
        k = 0
        while k <= steps:
            la, lo = chord_sample(ax, ay, az, bx, by, bz, k / steps)
            if not count:
                ci = min(max(int((la + 90.0) * c_inv), 0), c_lat - 1)
                # chord samples come back with lo in [-180, 180] (atan2): no wrapping needed
                cj = min(max(int((lo + 180.0) * c_inv), 0), c_lon - 1)
                if not coarse[ci, cj] and clear_deg[ci, cj] > per_step:
                    k += 1 + int(clear_deg[ci, cj] / per_step)
                    continue
            y = (la + 90.0) * inv
            x = (lo + 180.0) * inv
            i = min(max(int(y), 0), n_lat - 1)
            j = min(max(int(x), 0), n_lon - 1)
            d = coast_dist[i, j]
            if count:  # on land already: the verdict stands, the count only grades it
                if d < 0:  # inland: every sample within -d is in land cells
                    n = min(1 + int(-d * unit_deg / per_step), steps - k + 1)
                else:  # sea or coast: one sample stands for the next _GRADE_STEP
                    n = min(_GRADE_STEP, steps - k + 1)
                    if d > 0 or raster[i, j] == 0:
                        n = -n
                count += max(n, 0)
                k += abs(n)
                continue
            if d > 0:  # sea cell: every sample within d is in sea cells
                k += 1 + int(d * unit_deg / per_step)
                continue
            v = raster[i, j]
            if v == 1:
                count += 1
            elif v == 2:
                key = i * n_lon + j
                slot = np.searchsorted(fine_keys, key)
                if slot >= fine_keys.size or fine_keys[slot] != key:
                    unresolved = True
                    if n_miss < missing.size and (n_miss == 0 or missing[n_miss - 1] != key):
                        missing[n_miss] = key
                        n_miss += 1
                elif fine[slot, min(int((y - i) * f), f - 1), min(int((x - j) * f), f - 1)]:
                    count += 1
            k += 1
        # an unresolved cell met before the first hit may be land: the count (a graded
        # violation) would then start later than once the cell is known, so the segment is
        # scanned again in either case and a plan never depends on what was resolved before
        out[s] = -1 if unresolved else count
    return n_miss
