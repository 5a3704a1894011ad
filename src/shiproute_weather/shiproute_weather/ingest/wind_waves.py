"""Sea state estimated from the wind when a forecast has wind but no waves.

The wind sea grows through the forecast's valid times with the JONSWAP fetch laws and the
SPM (1984) equivalent-duration method, capped at Pierson-Moskowitz (`wave_growth.grow_step`,
the same physics as the bundled scenarios); the fetch is the distance upwind to land on the
GSHHG-based 10' mask (`physics.fetch.fetch_by_direction_m`, open sea up to 2000 km). The first
wind is taken to have blown for `SPIN_UP_H` before the first valid time. No swell is
estimated (it comes from storms outside the wind field's memory), so the estimate is the wind
sea alone and the total sea equals it: a lower bound on the real sea state where swell runs.
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from shiproute_core.units import S_PER_HOUR

from ..contract import canonical as cv
from ..physics.fetch import direction_bin, fetch_by_direction_m
from ..physics.landmask import sea_mask
from ..physics.wave_growth import grow_step, jonswap_tm01_over_tp

#: the first valid time's wind is taken to have blown this long already [h]
SPIN_UP_H = 24.0
#: the fetch field is computed on at most this many grid nodes (a coarser stride beyond)
FETCH_MAX_NODES = 60_000
WIND_SEA_GAMMA = 3.3
ESTIMATE_NOTE = ("waves estimated from wind (JONSWAP fetch/duration-limited wind sea, SPM 1984 "
                 f"equivalent duration, {SPIN_UP_H:g} h spin-up, fetch to land from GSHHG, "
                 "no swell)")


def _fetch(lat: np.ndarray, lon: np.ndarray, sea: np.ndarray) -> np.ndarray:
    """(16, n_lat, n_lon) upwind fetch [m], computed on a thinned grid for large grids."""
    stride = 1
    while -(-lat.size // stride) * -(-lon.size // stride) > FETCH_MAX_NODES:
        stride += 1
    if stride == 1 or lat.size < 2 or lon.size < 2:
        return fetch_by_direction_m(sea, lat, lon)
    coarse = fetch_by_direction_m(sea[::stride, ::stride], lat[::stride], lon[::stride])
    iy = np.minimum(np.rint(np.arange(lat.size) / stride).astype(int), coarse.shape[1] - 1)
    ix = np.minimum(np.rint(np.arange(lon.size) / stride).astype(int), coarse.shape[2] - 1)
    return coarse[:, iy[:, None], ix[None, :]]


def estimate_waves(ds: xr.Dataset) -> xr.Dataset:
    """`ds` with total sea and wind sea (Hs, from-direction, Tm01) grown from its 10 m wind."""
    lat = ds["latitude"].values.astype(np.float64)
    lon = ds["longitude"].values.astype(np.float64)
    spacing = float(abs(lat[1] - lat[0])) if lat.size > 1 else 0.5
    sea = sea_mask(lat, lon, spacing)
    fetch = _fetch(lat, lon, sea)
    u_all, v_all = ds[cv.WIND_U].values, ds[cv.WIND_V].values
    t_s = cv.times_posix_s(ds)
    shape = u_all.shape
    hs_out = np.empty(shape, dtype=np.float32)
    tm_out = np.empty(shape, dtype=np.float32)
    dir_out = np.empty(shape, dtype=np.float32)
    ratio = jonswap_tm01_over_tp(WIND_SEA_GAMMA)
    land = np.where(sea, 0.0, np.nan)
    hs = np.zeros(shape[1:])
    prev_dir = None
    for i in range(shape[0]):
        u = np.nan_to_num(u_all[i].astype(np.float64))
        v = np.nan_to_num(v_all[i].astype(np.float64))
        speed = np.hypot(u, v)
        from_deg = np.rad2deg(np.arctan2(-u, -v)) % 360.0
        dt = SPIN_UP_H * S_PER_HOUR if i == 0 else float(t_s[i] - t_s[i - 1])
        f = np.take_along_axis(fetch, direction_bin(from_deg)[None], axis=0)[0]
        hs, tp = grow_step(hs, from_deg if prev_dir is None else prev_dir, speed, from_deg,
                           f, dt)
        prev_dir = from_deg
        missing = np.isnan(u_all[i]) | np.isnan(v_all[i])
        hs_out[i] = np.where(missing, np.nan, hs + land)
        tm_out[i] = np.where(missing, np.nan, tp * ratio + land)
        dir_out[i] = np.where(missing, np.nan, from_deg + land)
    dims = ("time", "latitude", "longitude")
    src = str(ds[cv.WIND_U].attrs.get("source_file", ds.attrs.get("source_files", "")))
    out = ds.copy()
    for names in ((cv.WAVE_HS, cv.WAVE_DIR, cv.WAVE_TM),
                  (cv.WIND_WAVE_HS, cv.WIND_WAVE_DIR, cv.WIND_WAVE_TM)):
        for n, a in zip(names, (hs_out, dir_out, tm_out), strict=True):
            out[n] = xr.DataArray(a if names[0] == cv.WAVE_HS else a.copy(), dims=dims)
            out[n].attrs.update(source_file=src, source_variable="estimated from "
                                f"{cv.WIND_U}/{cv.WIND_V}", conversion=ESTIMATE_NOTE)
    out.attrs["waves_estimated"] = ESTIMATE_NOTE
    ordered = [n for n in cv.CANONICAL_ORDER if n in out] + [
        n for n in out.data_vars if n not in cv.CANONICAL_ORDER]
    return cv.annotate(out[ordered])


def has_waves(ds: xr.Dataset) -> bool:
    """Whether a canonical dataset holds any wave height (total, wind sea or swell)."""
    return any(n in ds for n in (cv.WAVE_HS, cv.WIND_WAVE_HS, cv.SWELL_HS))
