"""Fetch over a land/sea mask: the distance upwind to land for 16 wind from-directions.

Wind-sea growth is fetch-limited near coasts; both the scenario generator and the waves
estimated from a wind-only forecast use this walk on the forecast grid.
"""

from __future__ import annotations

import numpy as np

EARTH_RADIUS_M = 6_371_000.0
FETCH_STEP_M = 25_000.0
FETCH_MAX_M = 2_000_000.0
N_FETCH_DIRECTIONS = 16


def fetch_by_direction_m(sea: np.ndarray, lat: np.ndarray, lon: np.ndarray) -> np.ndarray:
    """Distance (m) upwind to land for each of 16 wind from-directions; (16, n_lat, n_lon).

    Walks upwind in 25 km steps; leaving the grid counts as open sea (fetch up to 2000 km).
    """
    dlat = lat[1] - lat[0]
    dlon = lon[1] - lon[0]
    lat_g, lon_g = np.meshgrid(lat, lon, indexing="ij")
    out = np.full((N_FETCH_DIRECTIONS, *sea.shape), FETCH_MAX_M)
    n_steps = int(FETCH_MAX_M / FETCH_STEP_M)
    for k_dir in range(N_FETCH_DIRECTIONS):
        theta = np.deg2rad(k_dir * 360.0 / N_FETCH_DIRECTIONS)
        found = ~sea
        fetch = np.where(found, 0.0, FETCH_MAX_M)
        for step in range(1, n_steps + 1):
            dist = step * FETCH_STEP_M
            la = lat_g + np.rad2deg(dist * np.cos(theta) / EARTH_RADIUS_M)
            lo = lon_g + np.rad2deg(dist * np.sin(theta) / (EARTH_RADIUS_M
                                                           * np.cos(np.deg2rad(lat_g))))
            iy = np.rint((la - lat[0]) / dlat).astype(int)
            ix = np.rint((lo - lon[0]) / dlon).astype(int)
            inside = (iy >= 0) & (iy < lat.size) & (ix >= 0) & (ix < lon.size)
            land = np.zeros_like(found)
            land[inside] = ~sea[iy[inside], ix[inside]]
            hit = land & ~found
            fetch[hit] = dist
            found |= hit
        out[k_dir] = fetch
    return out


def direction_bin(from_deg: np.ndarray) -> np.ndarray:
    """Index of the nearest of the 16 fetch directions."""
    return np.rint(from_deg / (360.0 / N_FETCH_DIRECTIONS)).astype(int) % N_FETCH_DIRECTIONS
