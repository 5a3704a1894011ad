"""Numba kernels of the fast evaluator's finish: leg ends with the ports cut off, and per-leg
constraint flags and violations.

They do per element what `evaluation.clear_ports` and `constraints.leg_flags_and_violation`
do with whole-array numpy passes (same operations in the same order, so the same bits), in
one pass instead of some forty array operations per population; `fast_finish` calls them and
the tests hold them to the numpy originals bit for bit.
"""

from __future__ import annotations

import numpy as np
from numba import njit

BIG = 1.7976931348623157e308  # what numpy.nan_to_num makes of +inf

# columns of the `checks` switch vector of `leg_constraints`
(C_HS, C_WIND, C_SURF, C_PARAM, C_SYNC, C_GROUP, C_ENGINE, C_UKC) = range(8)
N_CHECKS = 8
# rows of the float input stack `leg_f` of `leg_constraints`
(F_SLAM, F_WET, F_PROP, F_TURN, F_RPM, F_HS, F_WIND, F_UKC, F_LAT_END) = range(9)
N_LEG_F = 9
# rows of the boolean input stack `leg_b` (ship-model flags)
(B_SURF, B_PARAM, B_SYNC, B_GROUP, B_ENGINE) = range(5)
# columns of the scalar limit vector
(L_SLAM, L_WET, L_PROP, L_TURN, L_RPM_MIN, L_RPM_MAX, L_HS, L_WIND, L_LAT) = range(9)
N_LIMITS = 9
# flag bits (shiproute_core.flags), passed in so the kernel holds no copy of their values
(G_LAND, G_SLAM, G_WET, G_PROP, G_TURN, G_RPM, G_HS, G_WIND, G_SURF, G_PARAM, G_SYNC, G_GROUP,
 G_ENGINE, G_DEPTH, G_LAT) = range(15)
N_BITS = 15


@njit(cache=True, nogil=True)
def _nan_to_num(x: float) -> float:
    """numpy.nan_to_num of one value: NaN -> 0, +-inf -> +-largest float."""
    if x != x:
        return 0.0
    if x == np.inf:
        return BIG
    if x == -np.inf:
        return -BIG
    return x


@njit(cache=True, nogil=True)
def _excess(value: float, limit: float) -> float:
    """`constraints._excess` of one value: relative excess over `limit` (>= 0)."""
    d = _nan_to_num(value) - limit
    return (d if d > 0.0 else 0.0) / max(limit, 1e-9)


@njit(cache=True, nogil=True)
def port_cut_ends(lon, lat, distance_m, dep_lon, dep_lat, arr_lon, arr_lat, cut_m,
                  lon0, lat0, lon1, lat1):
    """`evaluation.clear_ports` into (pop, m) outputs: legs from nodes (pop, m + 1), the
    first/last `cut_m` cut off a leg that starts at the departure / ends at the arrival."""
    pop, m = distance_m.shape
    for p in range(pop):
        for k in range(m):
            x0, y0, x1, y1 = lon[p, k], lat[p, k], lon[p, k + 1], lat[p, k + 1]
            d = distance_m[p, k]
            q = cut_m / (d if (d != d or d > 1.0) else 1.0)
            frac = q if q != q else min(max(q, 0.0), 1.0)
            at_dep = abs(x0 - dep_lon) < 1e-9 and abs(y0 - dep_lat) < 1e-9
            at_arr = abs(x1 - arr_lon) < 1e-9 and abs(y1 - arr_lat) < 1e-9
            f0 = frac if at_dep else 0.0
            f1 = frac if at_arr else 0.0
            dx, dy = x1 - x0, y1 - y0
            lon0[p, k] = x0 + f0 * dx
            lat0[p, k] = y0 + f0 * dy
            lon1[p, k] = x1 - f1 * dx
            lat1[p, k] = y1 - f1 * dy


@njit(cache=True, nogil=True)
def _ship_terms(p, k, leg_f, leg_b, limits, checks, bits, f, v):
    """Seakeeping, heading change, RPM, wave/wind limits, IMO and engine terms of one leg,
    added to (f, v) in `leg_flags_and_violation`'s order."""
    for r, lim, g in ((F_SLAM, L_SLAM, G_SLAM), (F_WET, L_WET, G_WET),
                      (F_PROP, L_PROP, G_PROP)):
        ex = _excess(leg_f[r, p, k], limits[lim])
        if ex > 0.0:
            f |= bits[g]
            v = v + ex
    ex = _excess(abs(leg_f[F_TURN, p, k]), limits[L_TURN])
    if ex > 1e-9:
        f |= bits[G_TURN]
        v = v + ex
    rpm = leg_f[F_RPM, p, k]
    lo, hi = limits[L_RPM_MIN], limits[L_RPM_MAX]
    if rpm < lo - 1e-9 or rpm > hi + 1e-9:
        f |= bits[G_RPM]
        v = v + abs(rpm - min(max(rpm, lo), hi))
    for on, r, lim, g in ((C_HS, F_HS, L_HS, G_HS), (C_WIND, F_WIND, L_WIND, G_WIND)):
        if checks[on]:
            ex = _excess(leg_f[r, p, k], limits[lim])
            if ex > 0.0:
                f |= bits[g]
                v = v + ex
    for on, r, g in ((C_SURF, B_SURF, G_SURF), (C_PARAM, B_PARAM, G_PARAM),
                     (C_SYNC, B_SYNC, G_SYNC), (C_GROUP, B_GROUP, G_GROUP),
                     (C_ENGINE, B_ENGINE, G_ENGINE)):
        if checks[on] and leg_b[r, p, k]:
            f |= bits[g]
            v = v + 1.0
    return f, v


@njit(cache=True, nogil=True)
def leg_constraints(land, leg_f, leg_b, active, limits, checks, bits, flags, viol, row_flags):
    """Flags (uint32) and violations per leg (pop, m), and the OR of each row's flags:
    `constraints.leg_flags_and_violation` term by term, in its order (land, seakeeping,
    heading change, RPM, wave and wind limits, IMO checks, engine, depth, latitude)."""
    pop, m = land.shape
    for p in range(pop):
        row = np.uint32(0)
        for k in range(m):
            f = np.uint32(0)
            v = 0.0
            if active[p, k]:
                if land[p, k] > 0:
                    f |= bits[G_LAND]
                    v = v + (1.0 + land[p, k])
                f, v = _ship_terms(p, k, leg_f, leg_b, limits, checks, bits, f, v)
                if checks[C_UKC]:
                    u = leg_f[F_UKC, p, k]
                    short = -(0.0 if u != u else _nan_to_num(u))
                    if short > 0.0:
                        f |= bits[G_DEPTH]
                        v = v + (1.0 + short)
                lat_ex = abs(leg_f[F_LAT_END, p, k]) - limits[L_LAT]
                if lat_ex > 0.0:
                    f |= bits[G_LAT]
                    v = v + lat_ex
            flags[p, k] = f
            viol[p, k] = v
            row |= f
        row_flags[p] = row


@njit(cache=True, nogil=True)
def assemble_legs(sog, fuel_t_per_h, headings, heading_n, dist_n, dur_n, stage_s, duration,
                  distance, heading, fuel_t):
    """The fast evaluator's leg arrays (pop, m) of generated routes: every stage `stage_s`
    long over max(SOG, 0) x `stage_s` at its heading, the final connection (`heading_n`,
    `dist_n`, `dur_n`) last, fuel = rate x duration / 3600 (numpy's operations, in its
    order: the same bits as the whole-array version)."""
    pop, m = duration.shape
    n = m - 1
    for p in range(pop):
        for k in range(n):
            s = sog[p, k]
            duration[p, k] = stage_s
            distance[p, k] = (s if s != s or s > 0.0 else 0.0) * stage_s
            heading[p, k] = headings[p, k]
        duration[p, n] = dur_n[p]
        distance[p, n] = dist_n[p]
        heading[p, n] = heading_n[p]
        for k in range(m):
            fuel_t[p, k] = fuel_t_per_h[p, k] * duration[p, k] / 3600.0


@njit(cache=True, nogil=True)
def assemble_and_cut(sog, fuel_t_per_h, headings, heading_n, dist_n, dur_n, stage_s, lon, lat,
                     dep_lon, dep_lat, arr_lon, arr_lat, cuts_m, duration, distance, heading,
                     fuel_t, ends):
    """`assemble_legs`, then `port_cut_ends` for each cut in `cuts_m` into ends[4 c: 4 c + 4]
    (lon0, lat0, lon1, lat1 per cut): one compiled call per piece of rows."""
    assemble_legs(sog, fuel_t_per_h, headings, heading_n, dist_n, dur_n, stage_s, duration,
                  distance, heading, fuel_t)
    for c in range(cuts_m.size):
        port_cut_ends(lon, lat, distance, dep_lon, dep_lat, arr_lon, arr_lat, cuts_m[c],
                      ends[4 * c], ends[4 * c + 1], ends[4 * c + 2], ends[4 * c + 3])
