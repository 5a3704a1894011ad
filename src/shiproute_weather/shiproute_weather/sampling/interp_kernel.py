"""Numba kernel: NaN-aware trilinear (time, latitude, longitude) interpolation on a regular grid.

The field array may be float32/float64, or uint16 holding IEEE 754 binary16 (half precision)
bit patterns (see `half_kernel`): numba has no float16 on the CPU, so half-precision storage
is read through a 65,536-entry float32 table (256 kB, stays in cache).

Public API: `ForecastSampler` calls `trilinear`, and so may compiled code of other packages
(the planner's route kernels), with the arrays `sampler_arrays` exposes.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange, types
from numba.extending import overload

from .half_kernel import HALF_TO_FLOAT32

#: Minimum share of the interpolation weight that must fall on valid (non-NaN) nodes; below it
#: the result is NaN. At 0.5 a point is valued only when it is closer to sea nodes than land.
MIN_VALID_WEIGHT = 0.5


def node_value(data: np.ndarray, it: int, iy: int, ix: int, c: int) -> float:
    """Value of one grid node; decodes binary16 bit patterns held in a uint16 array."""
    v = data[it, iy, ix, c]
    return float(HALF_TO_FLOAT32[v]) if data.dtype == np.uint16 else float(v)


# numba caches overloads with this option; its typed options dict does not list the key
@overload(node_value, jit_options={"cache": True})  # type: ignore[typeddict-unknown-key]
def _node_value_impl(data, it, iy, ix, c):
    if data.dtype == types.uint16:
        def half(data, it, iy, ix, c):
            return HALF_TO_FLOAT32[data[it, iy, ix, c]]
        return half

    def plain(data, it, iy, ix, c):
        return data[it, iy, ix, c]
    return plain


@njit(cache=True, parallel=True, fastmath=False)
def trilinear(
    data: np.ndarray,  # (n_time, n_lat, n_lon, n_channel) float32, or uint16 binary16 bits
    times_s: np.ndarray,  # (n_time,) float64 ascending
    lat0: float, dlat: float, lon0: float, dlon: float, periodic: bool,
    lon_deg: np.ndarray, lat_deg: np.ndarray, t_s: np.ndarray,  # (n,) float64
    out: np.ndarray,  # (n_channel, n) float64
) -> None:
    """Fill `out` with interpolated channels; NaN outside the latitude/longitude domain."""
    nt, nlat, nlon, nch = data.shape
    n = lon_deg.shape[0]
    for p in prange(n):
        tp = t_s[p]
        y = (lat_deg[p] - lat0) / dlat
        x = ((lon_deg[p] - lon0) % 360.0) / dlon
        inside = tp == tp and y >= -1e-9 and y <= nlat - 1 + 1e-9
        if not periodic and x > nlon - 1 + 1e-9:
            # just below 360 deg from lon0 is lon0 itself seen from the other side
            if x * dlon > 360.0 - 1e-9:
                x = 0.0
            else:
                inside = False
        if not inside:
            for c in range(nch):
                out[c, p] = np.nan
            continue
        # time: clamp to the ends
        if nt == 1 or tp <= times_s[0]:
            it0, it1, wt = 0, 0, 0.0
        elif tp >= times_s[nt - 1]:
            it0, it1, wt = nt - 1, nt - 1, 0.0
        else:
            it1 = np.searchsorted(times_s, tp, side="right")
            it0 = it1 - 1
            wt = (tp - times_s[it0]) / (times_s[it1] - times_s[it0])
        # latitude
        y = min(max(y, 0.0), nlat - 1.0)
        iy0 = min(int(y), nlat - 2) if nlat > 1 else 0
        iy1 = iy0 + 1 if nlat > 1 else 0
        wy = y - iy0
        # longitude
        if periodic:
            fx = math.floor(x)
            ix0 = int(fx) % nlon
            ix1 = (ix0 + 1) % nlon
            wx = x - fx
        else:
            x = min(max(x, 0.0), nlon - 1.0)
            ix0 = min(int(x), nlon - 2) if nlon > 1 else 0
            ix1 = ix0 + 1 if nlon > 1 else 0
            wx = x - ix0
        for c in range(nch):
            acc = 0.0
            wsum = 0.0
            for k in range(8):
                itk = it1 if (k & 4) else it0
                iyk = iy1 if (k & 2) else iy0
                ixk = ix1 if (k & 1) else ix0
                w = (wt if (k & 4) else 1.0 - wt) * (wy if (k & 2) else 1.0 - wy) * (
                    wx if (k & 1) else 1.0 - wx)
                if w > 0.0:
                    v = node_value(data, itk, iyk, ixk, c)
                    if v == v:
                        acc += w * v
                        wsum += w
            out[c, p] = acc / wsum if wsum >= MIN_VALID_WEIGHT else np.nan
