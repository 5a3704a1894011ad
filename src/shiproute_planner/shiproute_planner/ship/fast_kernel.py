"""Numba kernel of the tabulated model: per-leg thrust balance, fuel, currents, seakeeping.

All tables are on uniform grids (O(1) lookups); the kernel mirrors ``physics`` term by
term. Angles enter the tables through cos(relative angle) so that each wave system costs
one cosine. The speed is found by a bracketed Newton iteration whose slope comes from the
same tables. Helpers that take arrays are inlined into their callers (`inline="always"`):
a compiled call counts references to each array argument with atomic operations, once per
leg and Newton step otherwise; inlined, the results are the same bits.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from shiproute_core.units import M_S_PER_KNOT

# indices into the scalar parameter vector ``par``
(P_RHO, P_D, P_T, P_ETA_R, P_ETA_S, P_JMAX, P_WMAX, P_KT0, P_KT1, P_KT2, P_KT3, P_KQ0, P_KQ1,
 P_KQ2, P_KQ3, P_AF, P_MCR, P_RPM_MCR, P_RPM_MIN, P_RPM_MAX, P_OVERLOAD, P_TORQUE, P_DV, P_NV,
 P_WDV, P_WNV, P_T0, P_DT, P_NT, P_SDV, P_SNV, P_NC, P_LPP, P_MIN_HS, P_TROLL, P_TOL,
 P_THR_SLAM, P_THR_WET, P_THR_PROP, P_CALM_K, P_VTOP, P_SURF_KN, P_POWER_K) = range(43)
N_PAR = 43
# P_POWER_K: share of the shaft power the weather adds at a given RPM that the model burns:
# 1 for the physics (the propeller, loaded, takes more torque), 0 for Kwon's method (the engine
# keeps its calm-water output while the ship slows), fitted for other tabulated models
G = 9.80665
RHO_AIR = 1.225
PEAK_ITTC = 1.0 / 0.772
PEAK_JONSWAP = 1.0 / 0.834
COS_45 = math.sqrt(0.5)


@njit(cache=True)
def grid_cell(x0, dx, n, x):
    """Cell index and fraction on a uniform grid, clamped to its ends."""
    u = (x - x0) / dx
    if u <= 0.0:
        return 0, 0.0
    if u >= n - 1:
        return n - 2, 1.0
    i = int(u)
    return i, u - i


@njit(cache=True, inline="always")
def _lin_cos(tab, c):
    """Linear interpolation of ``tab`` given on a uniform grid of cosines -1..1."""
    i, f = grid_cell(-1.0, 2.0 / (tab.size - 1), tab.size, c)
    return tab[i] * (1.0 - f) + tab[i + 1] * f


@njit(cache=True, inline="always")
def _lin_uniform(tab, x0, dx, x):
    """Linear interpolation on a uniform grid starting at x0 with spacing dx (clamped)."""
    i, f = grid_cell(x0, dx, tab.size, x)
    return tab[i] * (1.0 - f) + tab[i + 1] * f


@njit(cache=True)
def head_sea_taper(cos_rel):
    """STAWAVE-2 validity taper (1 inside +-45 deg of head seas, 0 from beam seas aft)."""
    if cos_rel >= COS_45:
        return 1.0
    if cos_rel <= 0.0:
        return 0.0
    x = (math.degrees(math.acos(cos_rel)) - 45.0) / 45.0
    return 0.5 * (1.0 + math.cos(math.pi * x))


@njit(cache=True, inline="always")
def _bilin(tab, iv, fv, it, ft, dv):
    """Bilinear value in (speed, period) and its slope along speed."""
    lo = tab[iv, it] * (1.0 - ft) + tab[iv, it + 1] * ft
    hi = tab[iv + 1, it] * (1.0 - ft) + tab[iv + 1, it + 1] * ft
    return lo * (1.0 - fv) + hi * fv, (hi - lo) / dv


@njit(cache=True, inline="always")
def _add_m0(tab, hs2, iv, fv, it, ft, ir, fr, m0):
    """m0[s] += Hs^2 * trilinear(tab[..., s]) over (speed, period, cos angle)."""
    for dv in range(2):
        wvv = fv if dv else 1.0 - fv
        for dt in range(2):
            wt = ft if dt else 1.0 - ft
            for dr in range(2):
                wgt = hs2 * wvv * wt * (fr if dr else 1.0 - fr)
                for s in range(3):
                    m0[s] += wgt * tab[iv + dv, it + dt, ir + dr, s]


@njit(cache=True, inline="always")
def resistance(v, par, r_calm, wake, u_ws, u_sw, a_ws, a_sw, it_ws, ft_ws, it_sw, ft_sw, w_fwd,
               w_side, caa):
    """Total resistance (N), its slope d/dV, wake fraction and its slope at ship speed v."""
    dv = par[P_DV]
    ic, fc = grid_cell(0.0, dv, int(par[P_NV]), v)
    r = r_calm[ic] * (1.0 - fc) + r_calm[ic + 1] * fc
    dr = (r_calm[ic + 1] - r_calm[ic]) / dv
    w = wake[ic] * (1.0 - fc) + wake[ic + 1] * fc
    dw = (wake[ic + 1] - wake[ic]) / dv
    if a_ws > 0.0 or a_sw > 0.0:
        # wave tables are uniform in sqrt(V): resolves the V^0.769 / Fr^1.5 onset near V = 0
        sv = math.sqrt(v)
        wdv = par[P_WDV] * 2.0 * max(sv, 1e-3)  # d(sqrt V) -> dV for the slope
        iv, fv = grid_cell(0.0, par[P_WDV], int(par[P_WNV]), sv)
        if a_ws > 0.0:
            x, dx = _bilin(u_ws, iv, fv, it_ws, ft_ws, wdv)
            r += a_ws * x
            dr += a_ws * dx
        if a_sw > 0.0:
            x, dx = _bilin(u_sw, iv, fv, it_sw, ft_sw, wdv)
            r += a_sw * x
            dr += a_sw * dx
    ax = w_fwd - v
    rel2 = ax * ax + w_side * w_side
    q = 0.5 * RHO_AIR * par[P_AF]
    c_head = caa[caa.size - 1]
    r -= q * c_head * v * v
    dr -= 2.0 * q * c_head * v
    if rel2 > 0.0:
        rel = math.sqrt(rel2)
        cos_rel = -ax / rel
        ci, cf = grid_cell(-1.0, 2.0 / (caa.size - 1), caa.size, cos_rel)
        c = caa[ci] * (1.0 - cf) + caa[ci + 1] * cf
        dc_dcos = (caa[ci + 1] - caa[ci]) * (caa.size - 1) / 2.0
        dcos_dv = w_side * w_side / (rel2 * rel)
        r += q * c * rel2
        dr += q * (dc_dcos * dcos_dv * rel2 - 2.0 * c * ax)
    return r, dr, w, dw


@njit(cache=True, inline="always")
def _residual(v, inv_nd, k_thr, par, r_calm, wake, u_ws, u_sw, a_ws, a_sw, it_ws, ft_ws, it_sw,
              ft_sw, w_fwd, w_side, caa):
    """Thrust (1 - t) - total resistance (N) and its slope d/dV at ship speed v."""
    r, dr, w, dw = resistance(v, par, r_calm, wake, u_ws, u_sw, a_ws, a_sw, it_ws, ft_ws, it_sw,
                              ft_sw, w_fwd, w_side, caa)
    j = v * (1.0 - w) * inv_nd
    dj = ((1.0 - w) - v * dw) * inv_nd
    kt = par[P_KT0] + j * (par[P_KT1] + j * (par[P_KT2] + j * par[P_KT3]))
    dkt = par[P_KT1] + j * (2.0 * par[P_KT2] + 3.0 * j * par[P_KT3])
    return kt * k_thr - r, dkt * dj * k_thr - dr


@njit(cache=True, nogil=True, inline="always")
def _solve(n, par, r_calm, wake, u_ws, u_sw, a_ws, a_sw, it_ws, ft_ws, it_sw, ft_sw, w_fwd,
           w_side, caa):
    """Speed through water (m/s) at shaft speed n (rps): Newton kept inside a sign bracket."""
    d = par[P_D]
    inv_nd = 1.0 / (n * d)
    k_thr = par[P_RHO] * n * n * d * d * d * d * (1.0 - par[P_T])
    lo = 0.0
    hi = par[P_JMAX] * n * d / (1.0 - par[P_WMAX])
    x = min(par[P_CALM_K] * n, 0.999 * hi)
    checked_zero = False
    for _ in range(60):
        f, df = _residual(x, inv_nd, k_thr, par, r_calm, wake, u_ws, u_sw, a_ws, a_sw, it_ws,
                          ft_ws, it_sw, ft_sw, w_fwd, w_side, caa)
        if f > 0.0:
            lo = x
        else:
            hi = x
        step = -f / df if df < 0.0 else -1e300
        xn = x + step
        if not lo < xn < hi:
            if xn <= lo and lo == 0.0 and not checked_zero:
                checked_zero = True
                f0, _ = _residual(0.0, inv_nd, k_thr, par, r_calm, wake, u_ws, u_sw, a_ws, a_sw,
                                  it_ws, ft_ws, it_sw, ft_sw, w_fwd, w_side, caa)
                if f0 <= 0.0:
                    return 0.0  # thrust cannot even hold the ship at rest
            xn = 0.5 * (lo + hi)
        if abs(xn - x) < 5e-3 or hi - lo < 1e-9:  # m/s; Newton: next error ~ step^2 << 1e-4
            return xn
        x = xn
    return x


@njit(cache=True, inline="always")
def _brake_power_kw(n, v, par, wake):
    """Brake power [kW] at shaft speed n (rps) and ship speed v (m/s): propeller torque."""
    d = par[P_D]
    ic, fc = grid_cell(0.0, par[P_DV], int(par[P_NV]), v)
    w = wake[ic] * (1.0 - fc) + wake[ic + 1] * fc
    j = v * (1.0 - w) / (n * d)
    kq = par[P_KQ0] + j * (par[P_KQ1] + j * (par[P_KQ2] + j * par[P_KQ3]))
    pb = 2.0 * math.pi * n * kq * par[P_RHO] * n * n * d * d * d * d * d / par[P_ETA_R]
    return pb / par[P_ETA_S] * 1e-3


@njit(cache=True, inline="always")
def _imo(par, v, hs, t_mean, cos_rel, peak, out):
    """OR the MSC.1/Circ.1228 flags of one wave system into out[0:4]."""
    if hs < par[P_MIN_HS]:
        return
    lpp = par[P_LPP]
    tp = t_mean * peak
    if cos_rel < -COS_45 and v / M_S_PER_KNOT * (-cos_rel) > par[P_SURF_KN]:
        out[0] = True  # surf-riding / broaching-to
    if G * tp * tp / (2.0 * math.pi) > 0.8 * lpp and hs > 0.04 * lpp:
        out[3] = True  # successive high-wave attack
    wp = 2.0 * math.pi / tp
    we = abs(wp + wp * wp * v * cos_rel / G)
    te = 2.0 * math.pi / max(we, 1e-6)
    tr = par[P_TROLL]
    if abs(cos_rel) >= COS_45 and abs(te / (0.5 * tr) - 1.0) < par[P_TOL]:
        out[1] = True  # parametric rolling (head or following sector only)
    if abs(te / tr - 1.0) < par[P_TOL]:
        out[2] = True  # synchronous rolling


# input checks done inside the kernel (cheap) instead of dozens of numpy passes per call:
# field id -> (lo, hi); the wrapper maps a failing id back to a name and message
CHECK_FIELDS = ("rpm", "heading_deg", "wind speed", "wind_wave_hs_m", "wind_wave_from_deg",
                "wind_wave_period_s", "swell_hs_m", "swell_from_deg", "swell_period_s",
                "current speed")


@njit(cache=True)
def _check(x, lo, hi):
    return lo <= x <= hi  # False for NaN


@njit(cache=True, nogil=True)
def check_kernel(rpm, hdg, wu, wv, ws_hs, ws_from, ws_t, sw_hs, sw_from, sw_t, cu, cv, limits,
                 start, stop):
    """Return (field id, leg index) of the first out-of-range input, or (-1, -1)."""
    for k in range(start, stop):
        vals = (rpm[k], hdg[k], math.sqrt(wu[k] * wu[k] + wv[k] * wv[k]), ws_hs[k], ws_from[k],
                ws_t[k], sw_hs[k], sw_from[k], sw_t[k], math.sqrt(cu[k] * cu[k] + cv[k] * cv[k]))
        for f in range(10):
            if not _check(vals[f], limits[f, 0], limits[f, 1]):
                return f, k
    return -1, -1


@njit(cache=True, nogil=True)
def evaluate_kernel(rpm, hdg, wu, wv, ws_hs, ws_from, ws_t, sw_hs, sw_from, sw_t, cu, cv,
                    par, r_calm, wake, u_ws, u_sw, m0_ws, m0_sw, caa, sfoc_x, sfoc_y,
                    out_f, out_b, start, stop):
    """Fill columns start..stop of out_f (11, N) and out_b (5, N); see ``fast.FastModel``."""
    m0 = np.zeros(3)
    flags = np.zeros(4, dtype=np.bool_)
    nc = int(par[P_NC])
    for k in range(start, stop):
        n = rpm[k] / 60.0
        h = math.radians(hdg[k])
        sh, ch = math.sin(h), math.cos(h)
        w_fwd = wu[k] * sh + wv[k] * ch
        w_side = wu[k] * ch - wv[k] * sh
        hs_ws2 = ws_hs[k] * ws_hs[k]
        hs_sw2 = sw_hs[k] * sw_hs[k]
        cos_ws = math.cos(math.radians(ws_from[k]) - h)
        cos_sw = math.cos(math.radians(sw_from[k]) - h)
        a_ws = hs_ws2 * head_sea_taper(cos_ws)
        a_sw = hs_sw2 * head_sea_taper(cos_sw)
        it_ws, ft_ws = grid_cell(par[P_T0], par[P_DT], int(par[P_NT]), ws_t[k])
        it_sw, ft_sw = grid_cell(par[P_T0], par[P_DT], int(par[P_NT]), sw_t[k])
        v = _solve(n, par, r_calm, wake, u_ws, u_sw, a_ws, a_sw, it_ws, ft_ws, it_sw, ft_sw,
                   w_fwd, w_side, caa)
        pb = _brake_power_kw(n, v, par, wake)
        if par[P_POWER_K] != 1.0:  # the weather's extra power, burnt only in part (Kwon: 0)
            v_calm = _solve(n, par, r_calm, wake, u_ws, u_sw, 0.0, 0.0, it_ws, ft_ws, it_sw,
                            ft_sw, 0.0, 0.0, caa)
            pb_calm = _brake_power_kw(n, v_calm, par, wake)
            pb = pb_calm + par[P_POWER_K] * (pb - pb_calm)
        load = pb / par[P_MCR]
        torque_ratio = load * par[P_RPM_MCR] / max(rpm[k], 1e-9)
        east = v * sh + cu[k]
        north = v * ch + cv[k]
        m0[:] = 0.0
        iv, fv = grid_cell(0.0, par[P_SDV], int(par[P_SNV]), v)
        if hs_ws2 > 0.0:
            ir, fr = grid_cell(-1.0, 2.0 / (nc - 1), nc, cos_ws)
            _add_m0(m0_ws, hs_ws2, iv, fv, it_ws, ft_ws, ir, fr, m0)
        if hs_sw2 > 0.0:
            ir, fr = grid_cell(-1.0, 2.0 / (nc - 1), nc, cos_sw)
            _add_m0(m0_sw, hs_sw2, iv, fv, it_sw, ft_sw, ir, fr, m0)
        for s in range(3):
            thr = par[P_THR_SLAM + s]
            if thr <= 0.0:
                out_f[8 + s, k] = 1.0
            elif m0[s] <= 1e-12:
                out_f[8 + s, k] = 0.0
            else:
                out_f[8 + s, k] = math.exp(-thr * thr / (2.0 * m0[s]))
        flags[:] = False
        _imo(par, v, ws_hs[k], ws_t[k], cos_ws, PEAK_ITTC, flags)
        _imo(par, v, sw_hs[k], sw_t[k], cos_sw, PEAK_JONSWAP, flags)
        out_f[0, k] = v
        out_f[1, k] = math.sqrt(east * east + north * north)
        cog = math.degrees(math.atan2(east, north))
        out_f[2, k] = cog + 360.0 if cog < 0.0 else cog
        out_f[3, k] = pb
        out_f[4, k] = pb * _lin_uniform(sfoc_y, sfoc_x[0], sfoc_x[1] - sfoc_x[0], load) * 1e-6
        out_f[5, k] = load
        out_f[6, k] = math.sqrt(hs_ws2 + hs_sw2)
        out_f[7, k] = math.sqrt(wu[k] * wu[k] + wv[k] * wv[k])
        out_b[0, k] = (rpm[k] < par[P_RPM_MIN] or rpm[k] > par[P_RPM_MAX]
                       or load > par[P_OVERLOAD] or torque_ratio > par[P_TORQUE])
        for i in range(4):
            out_b[1 + i, k] = flags[i]
