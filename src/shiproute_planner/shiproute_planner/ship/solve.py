"""Direct power method: the speed at which propeller thrust at given RPM balances resistance.

T(n, V) (1 - t) = R_total(V), with T = KT(J) rho n^2 D^4 and J = V (1 - w) / (n D)
(ISO 15016:2015 direct power method turned around: RPM given, speed sought). The root
is bracketed in [0, V(J = J_KT=0)] and found by the Illinois variant of regula falsi,
vectorised over all legs; where even V = 0 cannot be held (thrust < resistance) the
speed is 0.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .hull import ShipConstants

ResistanceFn = Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]


def thrust_n(c: ShipConstants, n_rps: np.ndarray, v: np.ndarray, wake: np.ndarray, d_m: float):
    """Open-water thrust (N) at ship speed ``v`` and shaft speed ``n_rps``."""
    j = v * (1.0 - wake) / (n_rps * d_m)
    return c.curve.kt(j) * c.rho_kg_m3 * n_rps**2 * d_m**4


def solve_speed(
    c: ShipConstants,
    n_rps: np.ndarray,
    d_m: float,
    total_resistance: ResistanceFn,
    tol_m_s: float = 1e-5,
    max_iter: int = 60,
) -> np.ndarray:
    """Speed through water (m/s) for 1-D arrays of shaft speed.

    ``total_resistance(v, idx)`` returns (R_total in N, wake fraction) for the legs ``idx``.
    """
    t = c.hm.thrust_deduction
    idx_all = np.arange(n_rps.size)

    def residual(v: np.ndarray, idx: np.ndarray) -> np.ndarray:
        r, w = total_resistance(v, idx)
        return thrust_n(c, n_rps[idx], v, w, d_m) * (1.0 - t) - r

    lo = np.zeros(n_rps.size)
    hi = c.j_max * n_rps * d_m / (1.0 - c.max_wake_fraction)
    f_lo = residual(lo, idx_all)
    f_hi = residual(hi, idx_all)
    v = np.zeros(n_rps.size)
    active = f_lo > 0.0
    side = np.zeros(n_rps.size, dtype=int)
    for _ in range(max_iter):
        idx = np.nonzero(active)[0]
        if idx.size == 0:
            break
        a, b, fa, fb = lo[idx], hi[idx], f_lo[idx], f_hi[idx]
        x = (a * fb - b * fa) / (fb - fa)
        x = np.where((x > a) & (x < b), x, 0.5 * (a + b))
        fx = residual(x, idx)
        left = fx * fa > 0  # root is in [x, b]
        s = side[idx]
        # Illinois: halve the retained end's value when the same side is kept twice
        fb_new = np.where(left & (s == 1), 0.5 * fb, fb)
        fa_new = np.where(~left & (s == -1), 0.5 * fa, fa)
        lo[idx] = np.where(left, x, a)
        f_lo[idx] = np.where(left, fx, fa_new)
        hi[idx] = np.where(left, b, x)
        f_hi[idx] = np.where(left, fb_new, fx)
        side[idx] = np.where(left, 1, -1)
        v[idx] = x
        done = (hi[idx] - lo[idx] < tol_m_s) | (np.abs(fx) < 1e-7 * np.abs(fa - fb) + 1.0)
        active[idx[done]] = False
    return v
