"""CF-packed NetCDF (int16 + scale_factor/add_offset, numeric fill values) decodes exactly.

Reference: the unpacked source values. Packing to int16 with step q rounds each value to
the nearest step, so the decoded value must lie within q/2 (plus float32 rounding) of the
source, and missing values (fill / missing_value) must come back as NaN at the same nodes.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr
from shiproute_weather.contract import canonical as cv
from shiproute_weather.ingest.cycle_builder import CycleConfig
from shiproute_weather.ingest.loaders import open_forecast
from shiproute_weather.ingest.stream import BLOCK_TIMES, load_slices
from shiproute_weather.wire.slices import slices_to_dataset
from weather_fixtures import small_canonical

STEP = 0.01  # packing step of every int16 variable


def _write_packed(ds: xr.Dataset, path: Path) -> Path:
    enc: dict[str, dict] = {}
    for n in ds.data_vars:
        offset = 180.0 if n in cv.DIRECTION_VARIABLES else 0.0
        enc[n] = {"dtype": "int16", "scale_factor": STEP, "add_offset": offset,
                  "_FillValue": np.int16(-32767)}
    # one float variable with a numeric (not NaN) missing value instead of packing
    enc[cv.WAVE_TM] = {"dtype": "float32", "_FillValue": np.float32(-9999.0),
                       "missing_value": np.float32(-9999.0)}
    enc["time"] = {"units": "hours since 2000-01-01 00:00:00", "dtype": "float64"}
    ds.to_netcdf(path, encoding=enc)
    return path


def _check_decoded(got: xr.Dataset, src: xr.Dataset) -> None:
    for n in src.data_vars:
        a, b = got[n].values, src[n].values
        np.testing.assert_array_equal(np.isnan(a), np.isnan(b), err_msg=n)
        ok = ~np.isnan(b)
        diff = a[ok].astype(np.float64) - b[ok]
        if n in cv.DIRECTION_VARIABLES:  # 359.996 may round to 360 and wrap to 0
            diff = (diff + 180.0) % 360.0 - 180.0
        tol = 0.0 if n == cv.WAVE_TM else STEP / 2 + 4e-7 * float(np.abs(b[ok]).max())
        assert float(np.abs(diff).max()) <= tol, n


def test_packed_file_decodes_in_full_and_streamed_loads(tmp_path: Path) -> None:
    src = small_canonical(n_time=BLOCK_TIMES + 5)  # the streamed load crosses a block edge
    p = _write_packed(src, tmp_path / "packed.nc")
    with xr.open_dataset(p, mask_and_scale=False) as raw:
        assert raw[cv.WIND_U].dtype == np.int16 and "scale_factor" in raw[cv.WIND_U].attrs
    full = open_forecast([p])
    _check_decoded(full, src)
    for n in full.data_vars:
        assert full[n].dtype == np.float32
        assert not {"scale_factor", "add_offset", "_FillValue"} & set(full[n].attrs), n
    _info, slices, _ = load_slices(str(p), CycleConfig())
    streamed = slices_to_dataset(slices)
    _check_decoded(streamed, src)
    for n in src.data_vars:
        np.testing.assert_array_equal(streamed[n].values, full[n].values, err_msg=n)
