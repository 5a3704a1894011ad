"""Swell radiated by a moving storm: dispersive arrival, spreading and dissipation (numba).

Each 3-hourly storm position emits swell with the wind-sea height and peak period found in its
core. At distance d and time t after emission, deep-water dispersion selects the period whose
group velocity c_g = g T / (4 pi) covers d in that time: T = 4 pi d / (g t). Energy arriving
is the source energy times a Gaussian spectral window around the source peak period, the
finite-source spreading R0 / (R0 + d), a dissipation exp(-d / L) with L = 4000 km (swell
e-folding scales of 3,000 to >20,000 km were observed by Ardhuin et al. 2009, J. Phys.
Oceanogr. 39, 2820-2838) and a directional factor favouring the storm's direction of travel.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange
from shiproute_core.units import S_PER_HOUR

G = 9.81
DISSIPATION_LENGTH_M = 4.0e6
SPECTRAL_WIDTH = 0.2  # relative std of period around the source peak period
RADIATED_SHARE = 0.5  # share of the source energy leaving the storm as swell in one direction


def distances_and_bearings(src_lat: np.ndarray, src_lon: np.ndarray, lat: np.ndarray,
                           lon: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Great-circle distance (m) and initial bearing (deg, point -> source) per source and node.

    Shapes (n_src, n_lat, n_lon) from source vectors and 1-D grid coordinates.
    """
    la1 = np.deg2rad(lat)[None, :, None]
    lo1 = np.deg2rad(lon)[None, None, :]
    la2 = np.deg2rad(src_lat)[:, None, None]
    lo2 = np.deg2rad(src_lon)[:, None, None]
    dlo = lo2 - lo1
    a = np.sin((la2 - la1) / 2) ** 2 + np.cos(la1) * np.cos(la2) * np.sin(dlo / 2) ** 2
    d = 2 * 6_371_000.0 * np.arcsin(np.sqrt(np.clip(a, 0, 1)))
    y = np.sin(dlo) * np.cos(la2)
    x = np.cos(la1) * np.sin(la2) - np.sin(la1) * np.cos(la2) * np.cos(dlo)
    return d.astype(np.float64), (np.rad2deg(np.arctan2(y, x)) % 360.0).astype(np.float64)


@njit(cache=True, parallel=True)
def radiate(times_h: np.ndarray, src_h: np.ndarray, src_hs: np.ndarray, src_tp: np.ndarray,
            src_heading_deg: np.ndarray, src_radius_m: np.ndarray, dist_m: np.ndarray,
            bearing_deg: np.ndarray, dt_src_h: float) -> tuple[np.ndarray, np.ndarray,
                                                                np.ndarray, np.ndarray]:
    """Swell energy (m^2, Hs^2/16), energy-weighted sin/cos of from-direction and E/T sums.

    `times_h` must be evenly spaced. The spectral window is cut at 3 standard deviations.

    Returns arrays (n_time, n_lat, n_lon): energy, e_sin, e_cos, e_over_t.
    """
    nt = times_h.shape[0]
    ns, ny, nx = dist_m.shape
    t0_h = times_h[0]
    dt_h = times_h[1] - times_h[0] if nt > 1 else 1.0  # valid times are evenly spaced
    # accumulate cell-major (time innermost) for cache locality; transposed on return
    energy = np.zeros((ny, nx, nt))
    e_sin = np.zeros((ny, nx, nt))
    e_cos = np.zeros((ny, nx, nt))
    e_over_t = np.zeros((ny, nx, nt))
    for cell in prange(ny * nx):
        iy = cell // nx
        ix = cell % nx
        for s in range(ns):
            d = dist_m[s, iy, ix]
            r0 = src_radius_m[s]
            if d < 0.5 * r0 or src_hs[s] <= 0.0:
                continue
            brg = bearing_deg[s, iy, ix]
            out_dir = math.radians(brg + 180.0)  # direction of travel from source to point
            directional = 0.55 + 0.45 * math.cos(out_dir - math.radians(src_heading_deg[s]))
            e_src = RADIATED_SHARE * src_hs[s] ** 2 / 16.0
            taper = 1.0 - math.exp(-((d / (1.5 * r0)) ** 2))
            decay = r0 / (r0 + d) * math.exp(-d / DISSIPATION_LENGTH_M)
            sb = math.sin(math.radians(brg))
            cb = math.cos(math.radians(brg))
            # only valid times whose dispersive period lies within 3 sigma of the source peak
            tp = src_tp[s]
            age_lo_h = (4.0 * math.pi * d / (G * tp * (1.0 + 3.0 * SPECTRAL_WIDTH))
                        / S_PER_HOUR)
            age_hi_h = (4.0 * math.pi * d / (G * tp * max(1.0 - 3.0 * SPECTRAL_WIDTH, 0.1))
                        / S_PER_HOUR)
            it_lo = max(0, math.ceil((src_h[s] + age_lo_h - t0_h) / dt_h))
            it_hi = min(nt - 1, math.floor((src_h[s] + age_hi_h - t0_h) / dt_h))
            for it in range(it_lo, it_hi + 1):
                age_s = (times_h[it] - src_h[s]) * S_PER_HOUR
                if age_s <= 0.0:
                    continue
                period = 4.0 * math.pi * d / (G * age_s)
                z = (period - tp) / (SPECTRAL_WIDTH * tp)
                if z * z > 9.0:
                    continue
                window = math.exp(-0.5 * z * z)
                # emissions every dt_src_h map onto a period interval dT = T dt / age
                norm = (dt_src_h * S_PER_HOUR / age_s) / (SPECTRAL_WIDTH * math.sqrt(2 * math.pi))
                e = e_src * window * norm * decay * directional * taper
                energy[iy, ix, it] += e
                e_sin[iy, ix, it] += e * sb
                e_cos[iy, ix, it] += e * cb
                e_over_t[iy, ix, it] += e / period
    return (energy.transpose(2, 0, 1), e_sin.transpose(2, 0, 1), e_cos.transpose(2, 0, 1),
            e_over_t.transpose(2, 0, 1))
