"""Sailing one leg between given points: steer so the course over ground hits the target."""

from __future__ import annotations

import numpy as np
from shiproute_core.geodesy import inverse

from .environment import PERF_FIELDS, Environment

MIN_SOG_M_S = 0.05


def perf_arrays(perf, shape: tuple[int, ...]) -> dict[str, np.ndarray]:
    """LegPerformance fields as float arrays of `shape`."""
    out = {}
    for k in PERF_FIELDS:
        a = np.asarray(getattr(perf, k), dtype=float)
        out[k] = a if a.shape == shape else np.broadcast_to(a, shape)
    return out


def sail_to(
    env: Environment,
    lon0: np.ndarray,
    lat0: np.ndarray,
    t0: np.ndarray,
    lon1: np.ndarray,
    lat1: np.ndarray,
    rpm: np.ndarray,
    iterations: int = 1,
) -> tuple[dict[str, np.ndarray], np.ndarray, np.ndarray, np.ndarray]:
    """Perform a leg from point 0 to point 1 at `rpm` in the weather met at point 0 and `t0`.

    The heading is corrected for current set (heading = course - drift) so the course over
    ground points at the target. Returns (performance arrays, heading_deg, distance_m,
    duration_s); zero-length legs take no time.
    """
    course, dist = inverse(lon0, lat0, lon1, lat1)
    sea = env.sea_state(lon0, lat0, t0)
    heading = course.copy()
    perf = env.perform(rpm, heading, sea)
    for _ in range(iterations):
        drift = (np.asarray(perf.cog_deg) - heading + 180.0) % 360.0 - 180.0
        if not np.any(np.abs(drift) > 1e-6):
            break
        heading = (course - drift) % 360.0
        perf = env.perform(rpm, heading, sea)
    arrays = perf_arrays(perf, course.shape)
    along = arrays["sog_m_s"] * np.cos(np.radians(arrays["cog_deg"] - course))
    speed = np.maximum(along, MIN_SOG_M_S)
    duration = np.where(dist > 0.0, dist / speed, 0.0)
    return arrays, heading, dist, duration
