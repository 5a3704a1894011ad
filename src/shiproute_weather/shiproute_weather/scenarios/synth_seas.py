"""Sea-state assembly for scenarios: background swell and partition combination."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class BackgroundSwell:
    """Seasonal swell from distant storms: height (m) field parameters, direction, period."""

    hs_m: float
    hs_extra_north_m: float
    from_deg: float
    period_s: float
    sheltered_west_of_lon_deg: float  # swell from the west is weaker close to Asia


MARCH_SWELL = BackgroundSwell(1.4, 1.4, 295.0, 11.5, 150.0)
JUNE_SWELL = BackgroundSwell(1.1, 0.2, 210.0, 13.0, 0.0)


def background_swell(spec: BackgroundSwell, lat: np.ndarray, lon: np.ndarray,
                     hours: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(hs_m, from_deg, period_s) of the background swell on the grid at a time."""
    lat_g, lon_g = np.meshgrid(lat, lon, indexing="ij")
    north = np.exp(-(((lat_g - 47.0) / 12.0) ** 2))
    slow = 1.0 + 0.15 * np.sin(2 * np.pi * hours / 96.0 + np.deg2rad(lon_g))
    hs = (spec.hs_m + spec.hs_extra_north_m * north) * slow
    if spec.sheltered_west_of_lon_deg > 0:
        shelter = np.clip((lon_g - 120.0) / (spec.sheltered_west_of_lon_deg - 120.0), 0.35, 1.0)
        hs = hs * shelter
    from_deg = spec.from_deg + 10.0 * np.sin(np.deg2rad(lat_g * 4.0) + hours / 50.0)
    period = spec.period_s + 1.0 * north
    return hs, from_deg % 360.0, period


def combine(parts: list[tuple[np.ndarray, np.ndarray, np.ndarray]]
            ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Combine sea partitions (hs, from_deg, tm01) by energy: Hs adds in quadrature, the mean
    period is m0/m1 (energy over sum of energy/period), the direction is the energy-weighted
    circular mean."""
    e = sum(h * h for h, _, _ in parts)
    e_over_t = sum(h * h / np.maximum(t, 1e-3) for h, _, t in parts)
    s = sum(h * h * np.sin(np.deg2rad(d)) for h, d, _ in parts)
    c = sum(h * h * np.cos(np.deg2rad(d)) for h, d, _ in parts)
    hs = np.sqrt(e)
    tm = np.where(e_over_t > 0, e / np.maximum(e_over_t, 1e-12), 0.0)
    direction = np.rad2deg(np.arctan2(s, c)) % 360.0
    return hs, direction, tm
