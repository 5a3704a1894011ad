"""Compiled angle helpers of the route and depth kernels."""

from __future__ import annotations

from numba import njit


@njit(cache=True, nogil=True)
def wrap360(x):
    """`x % 360.0` (Python's float modulo, bit for bit) without the library call where x lies
    within one turn of [0, 360): fmod returns x there, or x - 360 exactly (Sterbenz), and
    the sign correction adds 360 to a negative x."""
    if 0.0 < x < 360.0:
        return x
    if 360.0 <= x < 720.0:
        return x - 360.0
    if -360.0 < x < 0.0:
        return x + 360.0
    return x % 360.0  # zeros (+0.0 either way), NaN, far values
