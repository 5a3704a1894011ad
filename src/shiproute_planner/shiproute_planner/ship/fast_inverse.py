"""Compiled inverse of the tabulated model: RPM for a required speed through water.

With the speed given, resistance and wake follow directly from the tables; the shaft
speed then solves KT(J) rho n^2 D^4 (1 - t) = R with J = V (1 - w) / (n D), i.e.
KT(J) / J^2 = R / ((1 - t) rho D^2 V_A^2), monotone in J on (0, J_KT=0).
"""

from __future__ import annotations

import math

from numba import njit

from . import fast_kernel as fk


@njit(cache=True)
def _advance_ratio(par, c):
    """Root of KT(J) - c J^2 on (0, J_max): bracketed Newton."""
    lo, hi = 1e-6, par[fk.P_JMAX]
    j = 0.5 * hi
    for _ in range(60):
        kt = par[fk.P_KT0] + j * (par[fk.P_KT1] + j * (par[fk.P_KT2] + j * par[fk.P_KT3]))
        dkt = par[fk.P_KT1] + j * (2.0 * par[fk.P_KT2] + 3.0 * j * par[fk.P_KT3])
        g = kt - c * j * j
        if g > 0.0:
            lo = j
        else:
            hi = j
        dg = dkt - 2.0 * c * j
        jn = j - g / dg if dg < 0.0 else 0.5 * (lo + hi)
        if not lo < jn < hi:
            jn = 0.5 * (lo + hi)
        if abs(jn - j) < 1e-10:
            return jn
        j = jn
    return j


@njit(cache=True, nogil=True)
def rpm_kernel(stw, hdg, wu, wv, ws_hs, ws_from, ws_t, sw_hs, sw_from, sw_t, par, r_calm, wake,
               u_ws, u_sw, caa, out):
    """Fill ``out`` with the RPM per leg; return the first leg index whose thrust would be <= 0."""
    d = par[fk.P_D]
    for k in range(stw.size):
        v = stw[k]
        h = math.radians(hdg[k])
        sh, ch = math.sin(h), math.cos(h)
        cos_ws = math.cos(math.radians(ws_from[k]) - h)
        cos_sw = math.cos(math.radians(sw_from[k]) - h)
        a_ws = ws_hs[k] * ws_hs[k] * fk.head_sea_taper(cos_ws)
        a_sw = sw_hs[k] * sw_hs[k] * fk.head_sea_taper(cos_sw)
        it_ws, ft_ws = fk.grid_cell(par[fk.P_T0], par[fk.P_DT], int(par[fk.P_NT]), ws_t[k])
        it_sw, ft_sw = fk.grid_cell(par[fk.P_T0], par[fk.P_DT], int(par[fk.P_NT]), sw_t[k])
        r, _, w, _ = fk.resistance(v, par, r_calm, wake, u_ws, u_sw, a_ws, a_sw, it_ws, ft_ws,
                                   it_sw, ft_sw, wu[k] * sh + wv[k] * ch, wu[k] * ch - wv[k] * sh,
                                   caa)
        thrust = r / (1.0 - par[fk.P_T])
        if thrust <= 0.0:
            return k
        va = v * (1.0 - w)
        j = _advance_ratio(par, thrust / (par[fk.P_RHO] * d * d * va * va))
        out[k] = 60.0 * va / (j * d)
    return -1
