"""Detours of a stale re-plan's seed: the previous route bent round the stretch where the new
forecast breaks it (a storm that moved onto the track), so a search too short for a cold
plan's seeds still starts from a feasible route close to the one the ship sails."""

from __future__ import annotations

import numpy as np
from shiproute_core.geodesy import direct, inverse

from .route.evaluation import RouteEvaluation
from .route.seeding import TrackSeed

# sideways displacements of the broken stretch [m], each side of the track: a storm's edge
# is tens to a few hundred kilometres from a track that meets it
DETOUR_OFFSETS_M = (150e3, 300e3, 500e3)
DETOUR_TAPER_M = 600e3  # the bend fades out over this much beyond the broken stretch
RETIME_SCALES = (0.99, 1.0, 1.01, 1.02, 1.04)  # RPM factors of retimed copies ...
RETIME_SLOPES = (-0.12, -0.06, 0.0, 0.06, 0.12)  # ... and their ramps over the stages
RETIMED_ROWS = 4  # best seeds retimed


def broken_stretch(ev: RouteEvaluation, row: int) -> tuple[float, float, float] | None:
    """(lon, lat) of the middle of the legs of route `row` that break a constraint, and the
    stretch's half length [m]; None when no leg does (lateness alone is no stretch)."""
    bad = np.flatnonzero(ev.leg_flags[row] != 0)
    if bad.size == 0:
        return None
    lon = np.concatenate([ev.lon_deg[row, bad], ev.lon_deg[row, bad + 1]])
    lat = np.concatenate([ev.lat_deg[row, bad], ev.lat_deg[row, bad + 1]])
    mid = int(np.argmin(np.abs(lon - np.mean(lon)) + np.abs(lat - np.mean(lat))))
    _, d = inverse(np.full(lon.size, lon[mid]), np.full(lon.size, lat[mid]), lon, lat)
    return float(lon[mid]), float(lat[mid]), float(np.max(d))


def detour_seeds(seed: TrackSeed, centre: tuple[float, float, float]) -> list[TrackSeed]:
    """`seed`'s polyline with its nodes near `centre` (lon, lat, half length) moved sideways
    by each of DETOUR_OFFSETS_M to either side (a cos^2 taper to zero DETOUR_TAPER_M beyond
    the stretch; the ends stay), its RPMs scaled by the longer length (speed ~ RPM)."""
    lon, lat = np.asarray(seed.lon_deg, float), np.asarray(seed.lat_deg, float)
    if lon.size < 3:
        return []
    c_lon, c_lat, half_m = centre
    _, dist = inverse(np.full(lon.size, c_lon), np.full(lon.size, c_lat), lon, lat)
    reach = half_m + DETOUR_TAPER_M
    weight = np.cos(0.5 * np.pi * np.clip((dist - half_m) / DETOUR_TAPER_M, 0.0, 1.0)) ** 2
    weight[dist > reach] = 0.0
    weight[[0, -1]] = 0.0
    course, _ = inverse(lon[:-1], lat[:-1], lon[1:], lat[1:])
    node_course = np.concatenate([[course[0]], course])  # course into each node
    length = _length_m(lon, lat)
    out = []
    for off in DETOUR_OFFSETS_M:
        for side in (-90.0, 90.0):
            d_lon, d_lat = direct(lon, lat, node_course + side, off * weight)
            d_lon, d_lat = np.asarray(d_lon, float), np.asarray(d_lat, float)
            scale = _length_m(d_lon, d_lat) / max(length, 1.0)
            out.append(TrackSeed(f"{seed.source}_detour", d_lon, d_lat,
                                 np.asarray(seed.rpm, float) * scale))
    return out


def retimed_genes(x: np.ndarray, n_stages: int, lo: np.ndarray, hi: np.ndarray
                  ) -> np.ndarray:
    """Copies of genes `x` (rows) with their RPMs scaled by RETIME_SCALES and ramped by
    RETIME_SLOPES (relative change first to last stage / 2): passing a storm earlier or
    later, or making up the minutes a seed's conversion to stages lost, costs one
    evaluation of a small population instead of generations."""
    ramp = np.linspace(-1.0, 1.0, n_stages + 1)
    out = []
    for scale in RETIME_SCALES:
        for slope in RETIME_SLOPES:
            y = x.copy()
            y[:, n_stages:] *= scale * (1.0 + slope * ramp)[None, :]
            out.append(y)
    return np.clip(np.concatenate(out), lo, hi)


def _length_m(lon: np.ndarray, lat: np.ndarray) -> float:
    """Length of a polyline [m] (geodesic legs)."""
    return float(np.sum(inverse(lon[:-1], lat[:-1], lon[1:], lat[1:])[1]))
