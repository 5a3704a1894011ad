"""Validation errors name the file, the variable and what was expected."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from shiproute_weather.contract import canonical as cv
from shiproute_weather.contract.validate import validate
from shiproute_weather.errors import (
    ForecastFileError,
    MissingVariableError,
    ValueRangeError,
    VariableUnitsError,
    WeatherError,
)
from shiproute_weather.ingest.loaders import open_forecast
from weather_fixtures import small_canonical, write_nc


def test_wave_height_out_of_range(tmp_path: Path) -> None:
    # a dataset built in memory is checked whole (files are masked value by value on load:
    # test_outliers_and_bad_input)
    ds = small_canonical()
    ds[cv.WAVE_HS][0, 5, 5] = np.float32(31.0)
    with pytest.raises(ValueRangeError) as err:
        validate(ds, "bad_hs.nc")
    text = str(err.value)
    assert "bad_hs.nc" in text and cv.WAVE_HS in text and "0..30 m" in text


def test_wind_speed_limit_and_period_limit() -> None:
    ds = small_canonical()
    ds[cv.WIND_U][0, 0, 0] = np.float32(80.0)
    ds[cv.WIND_V][0, 0, 0] = np.float32(80.0)  # each component < 100, speed 113 m/s
    with pytest.raises(ValueRangeError, match="speeds below 100"):
        validate(ds, "x.nc")
    ds = small_canonical()
    ds[cv.SWELL_TM][1, 3, 3] = np.float32(-1.0)
    with pytest.raises(ValueRangeError, match=cv.SWELL_TM):
        validate(ds, "x.nc")


def test_nan_is_kept_and_allowed() -> None:
    ds = small_canonical()
    assert np.isnan(ds[cv.WAVE_HS].values).any()
    validate(ds, "x.nc")


def test_missing_and_required_variables(tmp_path: Path) -> None:
    ds = small_canonical()[[cv.WAVE_HS]]
    ds = ds.rename({cv.WAVE_HS: "temperature"})
    ds["temperature"].attrs = {"units": "K"}
    p = write_nc(ds, tmp_path / "no_vars.nc")
    with pytest.raises(MissingVariableError) as err:
        open_forecast([p])
    assert "no_vars.nc" in str(err.value) and "expected" in str(err.value)
    p2 = write_nc(small_canonical()[[cv.WAVE_HS]], tmp_path / "waves_only.nc")
    with pytest.raises(MissingVariableError, match=f"waves_only.nc.*{cv.WIND_U}"):
        open_forecast([p2], required=[cv.WIND_U])


def test_unknown_units_and_corrupt_files(tmp_path: Path) -> None:
    ds = small_canonical()[[cv.WAVE_HS]]
    ds[cv.WAVE_HS].attrs["units"] = "furlongs"
    p = write_nc(ds, tmp_path / "odd_units.nc")
    with pytest.raises(VariableUnitsError, match=r"odd_units\.nc.*furlongs"):
        open_forecast([p])
    junk = tmp_path / "junk.nc"
    junk.write_bytes(b"CDF\x01" + bytes(range(256)) * 4)
    with pytest.raises(ForecastFileError, match=r"junk\.nc"):
        open_forecast([junk])
    cut = tmp_path / "cut.nc"
    cut.write_bytes(write_nc(small_canonical(), tmp_path / "full.nc").read_bytes()[:3000])
    with pytest.raises(WeatherError, match=r"cut\.nc"):
        open_forecast([cut])
    with pytest.raises(ForecastFileError, match=r"missing\.nc"):
        open_forecast([tmp_path / "missing.nc"])
