"""Put a canonical dataset on another grid and other valid times, in numpy (no compiled kernel:
the weather node stays free of LLVM's resident memory).

Trilinear like the sampler: bilinear in latitude/longitude, linear in time; NaN nodes are
skipped and the weights renormalised when the valid ones carry at least `MIN_VALID_WEIGHT`;
directions are interpolated as unit vectors; times beyond the source are held at its edge
(callers decide how long: `combine`)."""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..contract import canonical as cv

#: the sampler's rule (`interp_kernel.MIN_VALID_WEIGHT`), kept here so numba is not imported
MIN_VALID_WEIGHT = 0.5


def _lat_weights(src: np.ndarray, dst: np.ndarray) -> tuple[np.ndarray, ...]:
    n = src.size
    y = (dst - src[0]) / (src[1] - src[0]) if n > 1 else np.zeros_like(dst)
    inside = (y >= -1e-9) & (y <= n - 1 + 1e-9)
    y = np.clip(y, 0.0, n - 1.0)
    i0 = np.minimum(np.floor(y).astype(np.int64), max(n - 2, 0))
    return i0, np.minimum(i0 + 1, n - 1), y - i0, inside


def _lon_weights(src: np.ndarray, dst: np.ndarray) -> tuple[np.ndarray, ...]:
    n = src.size
    step = src[1] - src[0] if n > 1 else 360.0
    periodic = abs(n * step - 360.0) < 1e-6 * max(1.0, step)
    x = ((dst - src[0]) % 360.0) / step
    if periodic:
        i0 = np.floor(x).astype(np.int64) % n
        return i0, (i0 + 1) % n, x - np.floor(x), np.ones(dst.size, dtype=bool)
    x = np.where((x > n - 1 + 1e-9) & (x * step > 360.0 - 1e-9), 0.0, x)
    inside = x <= n - 1 + 1e-9
    x = np.clip(x, 0.0, n - 1.0)
    i0 = np.minimum(np.floor(x).astype(np.int64), max(n - 2, 0))
    return i0, np.minimum(i0 + 1, n - 1), x - i0, inside


def _spatial(field: np.ndarray, ly: tuple, lx: tuple) -> tuple[np.ndarray, np.ndarray]:
    """(sum of weight x value over valid corners, sum of their weights) on the target grid."""
    acc = np.zeros((ly[0].size, lx[0].size))
    wsum = np.zeros_like(acc)
    for iy, wy in ((ly[0], 1.0 - ly[2]), (ly[1], ly[2])):
        rows = field[iy]
        for ix, wx in ((lx[0], 1.0 - lx[2]), (lx[1], lx[2])):
            v = rows[:, ix]
            w = wy[:, None] * wx[None, :]
            ok = ~np.isnan(v)
            acc += np.where(ok, v, 0.0) * w
            wsum += np.where(ok, w, 0.0)
    return acc, wsum


def regrid(ds: xr.Dataset, latitudes_deg: np.ndarray, longitudes_deg: np.ndarray,
           times: np.ndarray) -> xr.Dataset:
    """A canonical dataset's variables on other latitudes, longitudes and valid times."""
    ly = _lat_weights(ds["latitude"].values.astype(np.float64), latitudes_deg)
    lx = _lon_weights(ds["longitude"].values.astype(np.float64), longitudes_deg)
    outside = ~(ly[3][:, None] & lx[3][None, :])
    src_t = cv.times_posix_s(ds)
    dst_t = times.astype("datetime64[ns]").astype(np.int64).astype(np.float64) / 1e9
    k1 = np.clip(np.searchsorted(src_t, dst_t, side="right"), 1, max(src_t.size - 1, 1))
    k0 = k1 - 1 if src_t.size > 1 else np.zeros_like(k1)
    k1 = k1 if src_t.size > 1 else np.zeros_like(k1)
    span = np.where(src_t[k1] > src_t[k0], src_t[k1] - src_t[k0], 1.0)
    wt = np.clip((dst_t - src_t[k0]) / span, 0.0, 1.0)
    out = {}
    shape = (dst_t.size, latitudes_deg.size, longitudes_deg.size)
    for name in cv.present_variables(ds):
        a = ds[name].transpose("time", "latitude", "longitude").values
        parts = ([np.sin(np.deg2rad(a)), np.cos(np.deg2rad(a))] if name in
                 cv.DIRECTION_VARIABLES else [a])
        res = []
        cache: dict[int, tuple[np.ndarray, np.ndarray]] = {}
        for p_i, part in enumerate(parts):
            vals = np.empty(shape)
            for j in range(dst_t.size):
                sums = []
                for k in (int(k0[j]), int(k1[j])):
                    key = k * len(parts) + p_i
                    if key not in cache:
                        cache[key] = _spatial(part[k].astype(np.float64), ly, lx)
                    sums.append(cache[key])
                acc = (1.0 - wt[j]) * sums[0][0] + wt[j] * sums[1][0]
                wsum = (1.0 - wt[j]) * sums[0][1] + wt[j] * sums[1][1]
                with np.errstate(invalid="ignore", divide="ignore"):
                    v = np.where(wsum >= MIN_VALID_WEIGHT, acc / wsum, np.nan)
                v[outside] = np.nan
                vals[j] = v
            res.append(vals)
        data = (np.rad2deg(np.arctan2(res[0], res[1])) % 360.0 if len(res) == 2 else res[0])
        out[name] = (("time", "latitude", "longitude"), data.astype(np.float32),
                     dict(ds[name].attrs))
    coords = {"time": times, "latitude": latitudes_deg, "longitude": longitudes_deg}
    return cv.annotate(xr.Dataset(out, coords=coords, attrs=dict(ds.attrs)))
