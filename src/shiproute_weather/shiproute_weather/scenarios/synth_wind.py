"""Synthetic 10 m wind: seasonal background (trades, westerlies, waves) + Holland cyclone.

Holland, G. J. (1980), An analytic model of the wind and pressure profiles in hurricanes,
Mon. Wea. Rev. 108, 1212-1218: gradient wind
    V(r) = sqrt(B dp/rho (Rm/r)^B exp(-(Rm/r)^B) + (r f / 2)^2) - r f / 2,
reduced to 10 m by a surface factor, turned inward by an inflow angle (counter-clockwise in the
northern hemisphere) and made asymmetric by adding part of the translation velocity.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from shiproute_core.units import S_PER_HOUR

EARTH_RADIUS_M = 6_371_000.0
OMEGA_EARTH = 7.2921e-5
RHO_AIR = 1.15  # kg m-3
SURFACE_FACTOR = 0.8  # 10 m / gradient-level wind (marine boundary layer)
INFLOW_DEG = 20.0
TRANSLATION_SHARE = 0.5


@dataclass(frozen=True)
class Season:
    """Zonal-mean background wind and travelling-wave amplitude of one season."""

    westerly_peak_m_s: float
    westerly_lat_deg: float
    westerly_width_deg: float
    trade_peak_m_s: float
    trade_lat_deg: float
    wave_amplitude_m_s: float
    subpolar_easterly_m_s: float


# March: westerlies ~10 m/s near 40 N, NE trades ~7-8 m/s, active storm track; June: weaker.
MARCH = Season(10.0, 42.0, 10.0, 8.5, 15.0, 6.5, 6.5)
JUNE = Season(6.5, 45.0, 10.0, 7.5, 20.0, 3.5, 3.0)


@dataclass(frozen=True)
class TrackPoint:
    """Storm state at one time: centre, central pressure deficit, radius of max wind, B."""

    hours: float
    lat_deg: float
    lon_deg: float
    dp_hpa: float
    rmax_km: float
    holland_b: float


def background_wind(season: Season, lat_deg: np.ndarray, lon_deg: np.ndarray,
                    hours: float, phases: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Zonal-mean trades/westerlies plus non-divergent eastward-travelling waves (u, v m/s).

    `phases` (n_wave, 4) from the scenario's Generator: zonal wavenumber (k), meridional
    wavenumber (l), phase (rad) and phase speed (m/s) of each wave. Grids broadcast.
    """
    s = season
    u = (s.westerly_peak_m_s * np.exp(-(((lat_deg - s.westerly_lat_deg) / s.westerly_width_deg)
                                        ** 2))
         - s.trade_peak_m_s * np.exp(-(((lat_deg - s.trade_lat_deg) / 7.0) ** 2))
         - s.subpolar_easterly_m_s * np.exp(-(((lat_deg - 60.0) / 5.0) ** 2)))
    v = -0.4 * s.trade_peak_m_s * np.exp(-(((lat_deg - s.trade_lat_deg) / 7.0) ** 2))
    x_m = np.deg2rad(lon_deg) * EARTH_RADIUS_M * np.cos(np.deg2rad(45.0))
    y_m = np.deg2rad(lat_deg) * EARTH_RADIUS_M
    envelope = np.exp(-(((lat_deg - s.westerly_lat_deg) / 18.0) ** 2))
    t_s = hours * S_PER_HOUR
    amp = s.wave_amplitude_m_s / np.sqrt(phases.shape[0] / 2.0)
    for k, l_, ph, c in phases:
        arg = k * (x_m - c * t_s) + l_ * y_m + ph
        # psi = A/|K| sin(arg): u = -dpsi/dy, v = dpsi/dx (non-divergent)
        kk = np.hypot(k, l_)
        u = u - amp * envelope * (l_ / kk) * np.cos(arg)
        v = v + amp * envelope * (k / kk) * np.cos(arg)
    return u, v


def track_at(track: list[TrackPoint], hours: float) -> TrackPoint | None:
    """Storm state interpolated linearly in time; None before genesis or after decay."""
    if hours < track[0].hours or hours > track[-1].hours:
        return None
    h = np.array([p.hours for p in track])
    vals = np.array([[p.lat_deg, p.lon_deg, p.dp_hpa, p.rmax_km, p.holland_b] for p in track])
    row = [float(np.interp(hours, h, vals[:, i])) for i in range(vals.shape[1])]
    return TrackPoint(hours, *row)


def translation_m_s(track: list[TrackPoint], hours: float) -> tuple[float, float]:
    """Storm translation velocity (east, north) from the track by central differences."""
    a = track_at(track, max(hours - 1.5, track[0].hours))
    b = track_at(track, min(hours + 1.5, track[-1].hours))
    if a is None or b is None or b.hours <= a.hours:
        return 0.0, 0.0
    dt = (b.hours - a.hours) * S_PER_HOUR
    lat_mid = np.deg2rad(0.5 * (a.lat_deg + b.lat_deg))
    ue = np.deg2rad(b.lon_deg - a.lon_deg) * EARTH_RADIUS_M * np.cos(lat_mid) / dt
    vn = np.deg2rad(b.lat_deg - a.lat_deg) * EARTH_RADIUS_M / dt
    return float(ue), float(vn)


def local_offsets_m(lat_deg: np.ndarray, lon_deg: np.ndarray, lat_c: float,
                    lon_c: float) -> tuple[np.ndarray, np.ndarray]:
    """East/north offsets (m) of grid points from a centre (equirectangular, fine < 3000 km)."""
    dx = np.deg2rad(lon_deg - lon_c) * EARTH_RADIUS_M * np.cos(np.deg2rad(0.5 * (lat_deg + lat_c)))
    dy = np.deg2rad(lat_deg - lat_c) * EARTH_RADIUS_M
    return dx, dy


def holland_gradient_wind_m_s(r_m: np.ndarray, dp_pa: float, rmax_m: float, b: float,
                              f_s: float) -> np.ndarray:
    """Holland (1980) gradient wind speed at radius r (m/s)."""
    r = np.maximum(r_m, 1000.0)
    x = (rmax_m / r) ** b
    rf2 = r * abs(f_s) / 2.0
    return np.sqrt(b * dp_pa / RHO_AIR * x * np.exp(-x) + rf2 * rf2) - rf2


def cyclone_wind(track: list[TrackPoint], hours: float, lat_deg: np.ndarray,
                 lon_deg: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """10 m wind (u, v m/s) of the storm and a 0..1 weight of its core (0 without a storm)."""
    p = track_at(track, hours)
    zero = np.zeros(np.broadcast(lat_deg, lon_deg).shape)
    if p is None:
        return zero, zero.copy(), zero.copy()
    dx, dy = local_offsets_m(lat_deg, lon_deg, p.lat_deg, p.lon_deg)
    r = np.hypot(dx, dy)
    f = 2.0 * OMEGA_EARTH * np.sin(np.deg2rad(p.lat_deg))
    speed = SURFACE_FACTOR * holland_gradient_wind_m_s(r, p.dp_hpa * 100.0, p.rmax_km * 1e3,
                                                       p.holland_b, f)
    rs = np.maximum(r, 1.0)
    tx, ty = -dy / rs, dx / rs  # counter-clockwise tangent
    ix, iy = -dx / rs, -dy / rs  # inward
    a = np.deg2rad(INFLOW_DEG)
    u = speed * (np.cos(a) * tx + np.sin(a) * ix)
    v = speed * (np.cos(a) * ty + np.sin(a) * iy)
    ue, vn = translation_m_s(track, hours)
    core = np.exp(-((r / (2.5 * p.rmax_km * 1e3)) ** 2))
    u = u + TRANSLATION_SHARE * ue * core
    v = v + TRANSLATION_SHARE * vn * core
    return u, v, core


def total_wind(season: Season, track: list[TrackPoint], phases: np.ndarray, hours: float,
               lat_deg: np.ndarray, lon_deg: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Background + storm; the background is damped inside the storm core."""
    ub, vb = background_wind(season, lat_deg, lon_deg, hours, phases)
    if not track:
        return ub, vb
    uc, vc, core = cyclone_wind(track, hours, lat_deg, lon_deg)
    damp = 1.0 - 0.7 * core
    return ub * damp + uc, vb * damp + vc


def wave_phases(rng: np.random.Generator, n_wave: int = 6) -> np.ndarray:
    """Random travelling-wave parameters (k, l, phase, speed) for the background wind."""
    wavelength_m = rng.uniform(3.0e6, 6.5e6, n_wave)
    angle = rng.uniform(-0.6, 0.6, n_wave)
    kk = 2.0 * np.pi / wavelength_m
    return np.column_stack([kk * np.cos(angle), kk * np.sin(angle),
                            rng.uniform(0, 2 * np.pi, n_wave), rng.uniform(6.0, 12.0, n_wave)])
