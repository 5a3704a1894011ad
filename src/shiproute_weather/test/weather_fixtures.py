"""Small synthetic forecast files for tests (written in the tests, never downloaded)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr
from shiproute_weather.contract import canonical as cv


def small_canonical(n_time: int = 5, lat: tuple[float, float, float] = (30.0, 40.0, 0.5),
                    lon: tuple[float, float, float] = (170.0, 195.0, 0.5), seed: int = 1,
                    ref: str = "2026-03-03T12:00:00", cycle_id: str = "test-2026030312",
                    ) -> xr.Dataset:
    """Canonical dataset with smooth random fields and a NaN patch (land) in the waves."""
    rng = np.random.default_rng(seed)
    la = np.arange(lat[0], lat[1] + 1e-9, lat[2])
    lo = np.arange(lon[0], lon[1] + 1e-9, lon[2])
    times = np.datetime64(ref, "ns") + np.arange(n_time) * np.timedelta64(3, "h")
    shape = (n_time, la.size, lo.size)
    base = {
        cv.WIND_U: rng.normal(5, 6, shape), cv.WIND_V: rng.normal(0, 6, shape),
        cv.WAVE_HS: rng.uniform(0.5, 8, shape), cv.WAVE_DIR: rng.uniform(0, 360, shape),
        cv.WAVE_TM: rng.uniform(4, 14, shape),
        cv.WIND_WAVE_HS: rng.uniform(0.2, 5, shape), cv.WIND_WAVE_DIR: rng.uniform(0, 360, shape),
        cv.WIND_WAVE_TM: rng.uniform(2, 9, shape),
        cv.SWELL_HS: rng.uniform(0.2, 5, shape), cv.SWELL_DIR: rng.uniform(0, 360, shape),
        cv.SWELL_TM: rng.uniform(8, 16, shape),
        cv.CURRENT_U: rng.normal(0, 0.3, shape), cv.CURRENT_V: rng.normal(0, 0.3, shape),
    }
    land = np.zeros(shape[1:], bool)
    land[: la.size // 4, : lo.size // 5] = True
    data = {}
    for n, a in base.items():
        a = a.astype(np.float32)
        if n not in (cv.WIND_U, cv.WIND_V):
            a[:, land] = np.nan
        data[n] = (("time", "latitude", "longitude"), a)
    ds = xr.Dataset(data, coords={"time": times, "latitude": la, "longitude": lo},
                    attrs={"forecast_reference_time": ref + "Z", "source": "unit-test",
                           "cycle_id": cycle_id})
    return cv.annotate(ds)


def write_nc(ds: xr.Dataset, path: Path) -> Path:
    """Write as NetCDF4 (float32, zlib) with CF time units."""
    enc = {n: {"zlib": True, "dtype": "float32", "_FillValue": np.float32(np.nan)}
           for n in ds.data_vars}
    if "time" in ds.coords:
        enc["time"] = {"units": "hours since 2000-01-01 00:00:00", "dtype": "float64"}
    ds.to_netcdf(path, encoding=enc)
    return path
