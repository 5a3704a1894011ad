"""Numba kernels of the population evaluator: sea state from sampled channels, ship model
call, ellipsoidal geodesic steps, and the coarse land raster with its clear distances.

The ship model itself is `ship.fast_kernel.evaluate_kernel` (called, not copied); weather
sampling is the weather package's `trilinear` kernel, called by `fast_eval` before these.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..geo.angle_kernels import wrap360
from ..geo.clear_distance import clear_distance_deg  # noqa: F401 - polar-shrink reference
from ..ship import fast_kernel as fk

# canonical variables in the order of the `chan`/`isdir` arrays handed to `sea_and_perform`
SEA_VARIABLES = (
    "eastward_wind", "northward_wind",
    "sea_surface_wave_significant_height", "sea_surface_wave_from_direction",
    "sea_surface_wave_mean_period",
    "sea_surface_wind_wave_significant_height", "sea_surface_swell_wave_significant_height",
    "sea_surface_wind_wave_from_direction", "sea_surface_swell_wave_from_direction",
    "sea_surface_wind_wave_mean_period", "sea_surface_swell_wave_mean_period",
    "eastward_sea_water_velocity", "northward_sea_water_velocity",
)
G_M_S2 = 9.80665
A_M = 6378137.0  # WGS 84
F = 1.0 / 298.257223563
E2 = F * (2.0 - F)


@njit(cache=True, nogil=True)
def _direction_deg(s, co):
    """Direction [deg, 0..360) of a (sine, cosine) channel pair; NaN if either is NaN."""
    if s != s or co != co:
        return np.nan
    return wrap360(math.degrees(math.atan2(s, co)))


@njit(cache=True, nogil=True)
def _var(wx, chan, isdir, k, p):
    """Value of variable k at point p (NaN if absent); directions in degrees 0..360."""
    c = chan[k]
    if c < 0:
        return np.nan
    if isdir[k]:
        return _direction_deg(wx[c, p], wx[c + 1, p])
    return wx[c, p]


@njit(cache=True, nogil=True)
def _nz(x, default):
    return x if x == x else default


@njit(cache=True, nogil=True)
def _clip(x, lo, hi):
    return min(max(x, lo), hi)


@njit(cache=True, nogil=True)
def fill_sea(wx, chan, isdir, sea, limits):
    """Sea-state fields (10, P) from sampled channels: `SeaState.from_forecast` point-wise
    (after the environment's 0.5..30 s period clip), values clamped into the model's ranges."""
    n = sea.shape[1]
    pmin, pmax = limits[5, 0], limits[5, 1]
    hmax = limits[3, 1]
    val = np.empty(len(SEA_VARIABLES))
    for p in range(n):
        # every variable but the total sea's direction (needed only by fallbacks), read here
        # rather than by a call per variable (each would count references to the arrays)
        for k in range(val.size):
            c = chan[k]
            if k == 3 or c < 0:
                val[k] = np.nan
            elif isdir[k]:
                val[k] = _direction_deg(wx[c, p], wx[c + 1, p])
            else:
                val[k] = wx[c, p]
        u = _nz(val[0], 0.0)
        v = _nz(val[1], 0.0)
        tot_hs = _nz(val[2], 0.0)
        tot_t = val[4]
        tot_t = _nz(_clip(tot_t, 0.5, 30.0) if tot_t == tot_t else tot_t, 8.0)
        ws = val[5]
        sw = val[6]
        ws_dir = val[7]
        sw_dir = val[8]
        ws_t = val[9]
        sw_t = val[10]
        if ws_t == ws_t:
            ws_t = _clip(ws_t, 0.5, 30.0)
        if sw_t == sw_t:
            sw_t = _clip(sw_t, 0.5, 30.0)
        has_ws, has_sw = ws == ws, sw == sw
        speed = math.sqrt(u * u + v * v)
        pm_ws = min(tot_hs, 0.21 * speed * speed / G_M_S2)
        if has_ws:
            ws_hs = ws
        elif has_sw:
            ws_hs = math.sqrt(max(tot_hs * tot_hs - sw * sw, 0.0))
        else:
            ws_hs = pm_ws
        sw_hs = sw if has_sw else math.sqrt(max(tot_hs * tot_hs - ws_hs * ws_hs, 0.0))
        # the total-sea and wind directions (atan2 each) only where a fallback needs them
        if has_ws and ws_dir == ws_dir:
            ws_from = ws_dir
        elif has_sw or speed <= 0.5:
            ws_from = _nz(_var(wx, chan, isdir, 3, p), 0.0)
        else:
            ws_from = wrap360(math.degrees(math.atan2(-u, -v)))
        sea[0, p] = u
        sea[1, p] = v
        sea[2, p] = _clip(_nz(ws_hs, 0.0), 0.0, hmax)
        sea[3, p] = _nz(ws_from, 0.0)
        sea[4, p] = _clip(_nz(ws_t if has_ws and ws_t == ws_t else tot_t, 8.0), pmin, pmax)
        sea[5, p] = _clip(_nz(sw_hs, 0.0), 0.0, hmax)
        sea[6, p] = _nz(sw_dir if has_sw and sw_dir == sw_dir else _var(wx, chan, isdir, 3, p),
                        0.0)
        sea[7, p] = _clip(_nz(sw_t if has_sw and sw_t == sw_t else tot_t, 8.0), pmin, pmax)
        sea[8, p] = _nz(val[11], 0.0)
        sea[9, p] = _nz(val[12], 0.0)


@njit(cache=True, nogil=True)
def perform(rpm, hdg, sea, par, r_calm, wake, u_ws, u_sw, m0_ws, m0_sw, caa, sfoc_x, sfoc_y,
            out_f, out_b):
    """The ship model's compiled kernel on all P legs of one stage."""
    fk.evaluate_kernel(rpm, hdg, sea[0], sea[1], sea[2], sea[3], sea[4], sea[5], sea[6],
                       sea[7], sea[8], sea[9], par, r_calm, wake, u_ws, u_sw, m0_ws, m0_sw,
                       caa, sfoc_x, sfoc_y, out_f, out_b, 0, rpm.size)


@njit(cache=True, nogil=True)
def _geodesic_rate(phi, alpha):
    """d(phi, lambda, alpha)/ds of a geodesic on the WGS 84 ellipsoid (radians per metre)."""
    s = math.sin(phi)
    w2 = 1.0 - E2 * s * s
    n_r = A_M / math.sqrt(w2)
    m_r = A_M * (1.0 - E2) / (w2 * math.sqrt(w2))
    c = math.cos(phi)
    sa, ca = math.sin(alpha), math.cos(alpha)
    return ca / m_r, sa / (n_r * c), sa * s / (n_r * c)


@njit(cache=True, nogil=True)
def _sphere_direct(p, phi, lam, alpha, d, out_lon, out_lat):
    """Direct problem on the sphere of radius 6371 km (polar fallback)."""
    sig = d / 6_371_000.0
    s_phi = math.sin(phi) * math.cos(sig) + math.cos(phi) * math.sin(sig) * math.cos(alpha)
    phi2 = math.asin(min(1.0, max(-1.0, s_phi)))
    lam2 = lam + math.atan2(math.sin(alpha) * math.sin(sig) * math.cos(phi),
                            math.cos(sig) - math.sin(phi) * s_phi)
    out_lon[p] = math.degrees(lam2)
    out_lat[p] = math.degrees(phi2)


@njit(cache=True, nogil=True)
def direct_many(lon_deg, lat_deg, az_deg, dist_m, out_lon, out_lat):
    """Geodesic direct problem by RK4 on the geodesic ODE (steps <= 500 km; metres of error
    against Karney's solution below 75 deg latitude, measured in the tests). Above 75 deg
    (beyond any latitude bound) a spherical step avoids the ODE's polar singularity."""
    for p in range(lon_deg.size):
        d = dist_m[p]
        phi, lam, alpha = math.radians(lat_deg[p]), math.radians(lon_deg[p]), math.radians(
            az_deg[p])
        if abs(lat_deg[p]) + d / 111_000.0 > 75.0:
            _sphere_direct(p, phi, lam, alpha, d, out_lon, out_lat)
            continue
        nsub = 1 + int(abs(d) / 500_000.0)
        h = d / nsub
        for _ in range(nsub):
            k1 = _geodesic_rate(phi, alpha)
            k2 = _geodesic_rate(phi + 0.5 * h * k1[0], alpha + 0.5 * h * k1[2])
            k3 = _geodesic_rate(phi + 0.5 * h * k2[0], alpha + 0.5 * h * k2[2])
            k4 = _geodesic_rate(phi + h * k3[0], alpha + h * k3[2])
            phi += h / 6.0 * (k1[0] + 2.0 * k2[0] + 2.0 * k3[0] + k4[0])
            lam += h / 6.0 * (k1[1] + 2.0 * k2[1] + 2.0 * k3[1] + k4[1])
            alpha += h / 6.0 * (k1[2] + 2.0 * k2[2] + 2.0 * k3[2] + k4[2])
        out_lon[p] = math.degrees(lam)
        out_lat[p] = math.degrees(phi)


@njit(cache=True, nogil=True)
def inverse_many(lon0, lat0, lon1, lat1, out_az, out_dist):
    """Azimuth (auxiliary sphere of reduced latitudes) and Lambert's ellipsoidal distance
    (~10 m over thousands of km) from point 0 to point 1."""
    for p in range(lon0.size):
        b1 = math.atan((1.0 - F) * math.tan(math.radians(lat0[p])))
        b2 = math.atan((1.0 - F) * math.tan(math.radians(lat1[p])))
        dl = math.radians(lon1[p] - lon0[p])
        sb1, cb1, sb2, cb2 = math.sin(b1), math.cos(b1), math.sin(b2), math.cos(b2)
        y = math.sin(dl) * cb2
        x = cb1 * sb2 - sb1 * cb2 * math.cos(dl)
        out_az[p] = wrap360(math.degrees(math.atan2(y, x)))
        hav = math.sin(0.5 * (b2 - b1)) ** 2 + cb1 * cb2 * math.sin(0.5 * dl) ** 2
        sig = 2.0 * math.asin(min(1.0, math.sqrt(hav)))
        if sig < 1e-12:
            out_dist[p] = 0.0
            continue
        pp, qq = 0.5 * (b1 + b2), 0.5 * (b2 - b1)
        xx = (sig - math.sin(sig)) * math.sin(pp) ** 2 * math.cos(qq) ** 2 / math.cos(
            0.5 * sig) ** 2
        s2 = math.sin(0.5 * sig) ** 2
        yy = (sig + math.sin(sig)) * math.cos(pp) ** 2 * math.sin(qq) ** 2 / max(s2, 1e-300)
        out_dist[p] = A_M * (sig - 0.5 * F * (xx + yy))


def coarse_land_raster(raster: np.ndarray, factor: int) -> np.ndarray:
    """Boolean raster `factor` times coarser: any land/coast cell inside or in the 8
    neighbouring coarse cells (wrapping in longitude)."""
    n_lat, n_lon = raster.shape
    r = np.asarray(raster)[: n_lat - n_lat % factor, : n_lon - n_lon % factor]
    blocks = r.reshape(r.shape[0] // factor, factor, r.shape[1] // factor, factor)
    any_land = (blocks != 0).any(axis=(1, 3))
    out = any_land.copy()
    for di in (-1, 0, 1):
        for dj in (-1, 0, 1):
            shifted = np.roll(any_land, dj, axis=1)
            if di:
                shifted = np.roll(shifted, di, axis=0)
                if di > 0:
                    shifted[0] = any_land[0]
                else:
                    shifted[-1] = any_land[-1]
            out |= shifted
    return np.ascontiguousarray(out)
