"""Clear distances on global block rasters: how far one can go from a block before meeting a
flagged one (land, coast or shallows), the jump length of the compiled leg scans."""

from __future__ import annotations

import math

import numpy as np


def clear_distance_deg(flagged: np.ndarray, block_deg: float, max_abs_lat_deg: float = 72.0
                       ) -> np.ndarray:
    """Lower bound of the arc distance [deg] from anywhere in each block of a global raster
    (row 0 at 90 S, columns wrapping in longitude) to the nearest flagged block: Euclidean
    block distance with longitude blocks shrunk by cos(`max_abs_lat_deg`), minus a block
    diagonal; 0 poleward of `max_abs_lat_deg` (always sampled there)."""
    from scipy.ndimage import distance_transform_edt

    shrink = math.cos(math.radians(max_abs_lat_deg))
    tiled = np.concatenate([flagged, flagged, flagged], axis=1)  # wrap in longitude
    d = distance_transform_edt(~tiled, sampling=(1.0, shrink))[:, flagged.shape[1]:
                                                                 2 * flagged.shape[1]]
    out = np.maximum(d - 1.5, 0.0) * block_deg
    lat = -90.0 + (np.arange(flagged.shape[0]) + 0.5) * block_deg
    out[np.abs(lat) > max_abs_lat_deg - block_deg] = 0.0
    return np.ascontiguousarray(out.astype(np.float64))


def banded_clear_distance_deg(flagged: np.ndarray, block_deg: float, reach_deg: float = 10.0,
                              band_deg: float = 5.0, max_abs_lat_deg: float = 72.0
                              ) -> np.ndarray:
    """`clear_distance_deg` with the longitude shrink of each latitude band instead of the
    polar one, capped at `reach_deg`: on the sphere ds^2 >= dphi^2 + c^2 dlambda^2 wherever
    cos(lat) >= c, and a path shorter than the reach from a band stays within the band's
    poleward edge plus the reach, so c = cos(edge + reach) bounds every distance that
    matters from below (~2x longer jumps along mid-latitude routes than the polar shrink)."""
    from scipy.ndimage import distance_transform_edt

    n_lat, n_lon = flagged.shape
    lat = -90.0 + (np.arange(n_lat) + 0.5) * block_deg
    reach_rows = int(np.ceil(reach_deg / block_deg)) + 1
    tiled = np.concatenate([flagged, flagged, flagged], axis=1)  # wrap in longitude
    out = np.zeros((n_lat, n_lon))
    for lo in np.arange(-max_abs_lat_deg, max_abs_lat_deg, band_deg):
        rows = np.flatnonzero((lat >= lo) & (lat < lo + band_deg))
        if rows.size == 0:
            continue
        edge = max(abs(lo), abs(lo + band_deg)) + 0.5 * block_deg
        shrink = math.cos(math.radians(min(edge + reach_deg, 89.0)))
        a, b = max(rows[0] - reach_rows, 0), min(rows[-1] + reach_rows + 1, n_lat)
        d = distance_transform_edt(~tiled[a:b], sampling=(1.0, shrink))
        out[rows] = d[rows - a, n_lon:2 * n_lon]
    out = np.minimum(np.maximum(out - 1.5, 0.0) * block_deg, reach_deg)
    out[np.abs(lat) > max_abs_lat_deg - block_deg] = 0.0
    return np.ascontiguousarray(out)
