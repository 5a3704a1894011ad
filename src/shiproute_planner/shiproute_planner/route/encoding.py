"""Gene layout of a route (thesis eqs. 5-6): 2n + 1 floats per individual.

    x[:, 0]          theta_0: first heading, azimuth [deg true, going to]
    x[:, 1:n]        theta_1..theta_{n-1}: heading change relative to the previous stage [deg]
    x[:, n:2n+1]     rpm_0..rpm_n: shaft speed of stages 0..n-1 and of the final connection

Stage i (0 <= i < n) holds the absolute heading sum(theta_0..theta_i) for `stage_s`. The final
connection from node n to the arrival port has no heading gene: its course is the azimuth to the
port. Headings are what the ship steers; with current the track follows COG/SOG.
"""

from __future__ import annotations

import numpy as np
from shiproute_core.geodesy import inverse

from .problem import RouteProblem


def gene_bounds(problem: RouteProblem) -> tuple[np.ndarray, np.ndarray]:
    """Lower and upper bounds of every gene."""
    n = problem.n_stages
    lim = problem.limits
    az_gc = float(inverse(problem.dep_lon_deg, problem.dep_lat_deg,
                          problem.arr_lon_deg, problem.arr_lat_deg)[0])
    lo = np.empty(problem.n_var)
    hi = np.empty(problem.n_var)
    lo[0], hi[0] = az_gc - lim.first_heading_span_deg, az_gc + lim.first_heading_span_deg
    lo[1:n], hi[1:n] = -lim.max_heading_change_deg, lim.max_heading_change_deg
    lo[n:], hi[n:] = lim.rpm_min, lim.rpm_max
    return lo, hi


def split_genes(problem: RouteProblem, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Absolute stage headings (pop, n) [deg, 0..360) and RPMs (pop, n + 1)."""
    x = np.atleast_2d(np.asarray(x, dtype=float))
    n = problem.n_stages
    headings = np.cumsum(x[:, :n], axis=1) % 360.0
    return headings, x[:, n:]


def join_genes(headings_deg: np.ndarray, rpm: np.ndarray) -> np.ndarray:
    """Genes from absolute stage headings (pop, n) and RPMs (pop, n + 1)."""
    h = np.atleast_2d(np.asarray(headings_deg, dtype=float))
    rel = np.diff(h, axis=1)
    rel = (rel + 180.0) % 360.0 - 180.0
    return np.concatenate([h[:, :1], rel, np.atleast_2d(rpm)], axis=1)


def clip_genes(problem: RouteProblem, x: np.ndarray) -> np.ndarray:
    """Genes clipped into their bounds (the first heading is first brought near the bounds)."""
    lo, hi = gene_bounds(problem)
    x = np.array(x, dtype=float, copy=True)
    mid = 0.5 * (lo[0] + hi[0])
    x[:, 0] = mid + (x[:, 0] - mid + 180.0) % 360.0 - 180.0
    return np.clip(x, lo, hi)
