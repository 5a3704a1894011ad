"""Plausible North Pacific surface currents: Kuroshio + Extension, gyre flows, wind drift.

Jets are Gaussian in distance from a path (core speed and e-folding half width given per
path vertex); broad flows are zonal bands. Magnitudes follow textbook values (Kuroshio core
1-1.5 m/s narrowing to ~0.3 m/s in the Extension east of 160E; North Pacific Current and
North Equatorial Current 0.1-0.2 m/s; California Current ~0.1-0.2 m/s southward). A wind drift
of 1.5 % of the 10 m wind, turned 20 deg to the right (northern hemisphere), is added.
"""

from __future__ import annotations

import numpy as np

# (lat, lon, core speed m/s, half width km) along the Kuroshio and its Extension
KUROSHIO = np.array([
    [22.0, 122.5, 0.9, 60.0], [25.5, 123.5, 1.1, 60.0], [28.5, 127.5, 1.2, 60.0],
    [30.5, 131.0, 1.3, 60.0], [32.8, 135.5, 1.5, 60.0], [34.8, 140.5, 1.4, 70.0],
    [35.5, 145.0, 1.0, 90.0], [36.0, 150.0, 0.7, 110.0], [35.5, 156.0, 0.5, 140.0],
    [36.5, 165.0, 0.3, 200.0], [38.0, 175.0, 0.2, 250.0],
])
# Tsushima warm current through the Korea Strait into the Sea of Japan
TSUSHIMA = np.array([
    [32.0, 127.5, 0.4, 50.0], [34.0, 129.5, 0.5, 40.0], [37.0, 133.0, 0.35, 60.0],
    [40.0, 138.5, 0.3, 60.0], [41.5, 140.8, 0.5, 30.0],
])
WIND_DRIFT_SHARE = 0.015
WIND_DRIFT_TURN_DEG = 20.0
MAX_SPEED_M_S = 1.8


def _jet(path: np.ndarray, lat: np.ndarray, lon: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Velocity of a jet following `path` (densified), Gaussian across-stream."""
    n = 200
    s = np.linspace(0, len(path) - 1, n)
    idx = np.arange(len(path))
    p = np.column_stack([np.interp(s, idx, path[:, k]) for k in range(4)])
    lat_g, lon_g = np.meshgrid(lat, lon, indexing="ij")
    coslat = np.cos(np.deg2rad(lat_g))
    dx = (lon_g[..., None] - p[None, None, :, 1]) * 111.2 * coslat[..., None]
    dy = (lat_g[..., None] - p[None, None, :, 0]) * 111.2
    d2 = dx * dx + dy * dy
    k = np.argmin(d2, axis=-1)
    dist_km = np.sqrt(np.take_along_axis(d2, k[..., None], axis=-1)[..., 0])
    k0 = np.clip(k, 0, n - 2)
    tdx = (p[k0 + 1, 1] - p[k0, 1]) * np.cos(np.deg2rad(p[k0, 0]))
    tdy = p[k0 + 1, 0] - p[k0, 0]
    norm = np.hypot(tdx, tdy) + 1e-12
    speed = p[k, 2] * np.exp(-((dist_km / p[k, 3]) ** 2))
    return speed * tdx / norm, speed * tdy / norm


def steady_currents(lat: np.ndarray, lon: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Time-independent surface current (u, v m/s) on the grid (n_lat, n_lon)."""
    lat_g, lon_g = np.meshgrid(lat, lon, indexing="ij")
    u = (0.15 * np.exp(-(((lat_g - 43.0) / 5.0) ** 2))  # North Pacific Current
         - 0.18 * np.exp(-(((lat_g - 14.0) / 4.0) ** 2)))  # North Equatorial Current
    v = np.zeros_like(u)
    # California Current: southward along the American coast (lon ~ 230-242E, 25-48N)
    cal = np.exp(-(((lon_g - 234.0) / 4.0) ** 2)) * np.exp(-(((lat_g - 36.0) / 10.0) ** 2))
    v -= 0.15 * cal
    # Alaska Current / Alaskan Stream: anticlockwise round the Gulf of Alaska
    ak = np.exp(-(((lat_g - 56.0) / 2.5) ** 2)) * np.clip((lon_g - 185.0) / 40.0, 0, 1)
    u -= 0.2 * ak
    for path in (KUROSHIO, TSUSHIMA):
        uj, vj = _jet(path, lat, lon)
        u += uj
        v += vj
    return u, v


def with_wind_drift(u: np.ndarray, v: np.ndarray, wind_u: np.ndarray,
                    wind_v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Add the wind drift and cap the speed at MAX_SPEED_M_S."""
    a = np.deg2rad(-WIND_DRIFT_TURN_DEG)  # clockwise (to the right) in the NH
    du = WIND_DRIFT_SHARE * (wind_u * np.cos(a) - wind_v * np.sin(a))
    dv = WIND_DRIFT_SHARE * (wind_u * np.sin(a) + wind_v * np.cos(a))
    uu, vv = u + du, v + dv
    speed = np.hypot(uu, vv)
    scale = np.minimum(1.0, MAX_SPEED_M_S / np.maximum(speed, 1e-9))
    return uu * scale, vv * scale
