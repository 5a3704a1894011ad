"""Impossible values are masked and counted; files that cannot be a forecast are refused with
their name and the reason."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from shiproute_weather.contract import canonical as cv
from shiproute_weather.contract.record import load_notes
from shiproute_weather.errors import WeatherError
from shiproute_weather.ingest.loaders import open_forecast
from shiproute_weather.ingest.outliers import masked_counts
from weather_fixtures import small_canonical, write_nc


def _with(ds: xr.Dataset, name: str, index: tuple, value: float) -> None:
    ds[name].values[index] = value


def test_a_few_impossible_values_are_masked_and_counted(tmp_path: Path) -> None:
    ds = small_canonical(n_time=3)
    hs = ds[cv.WAVE_HS].values
    n = hs.size
    rng = np.random.default_rng(1)
    flat = rng.choice(n, size=12, replace=False)
    hs.reshape(-1)[flat[:4]] = 27.0  # rare but possible in a hurricane model: kept
    hs.reshape(-1)[flat[4:9]] = 99.0  # impossible: masked (5)
    ds[cv.WAVE_TM].values.reshape(-1)[flat[9:11]] = 0.0  # zero period: masked (2)
    ds[cv.WAVE_TM].values.reshape(-1)[flat[11]] = 55.0  # > 40 s: masked (1)
    _with(ds, cv.WIND_U, (0, 0, 0), 150.0)  # 150 m/s wind: masked with its v (1)
    _with(ds, cv.CURRENT_U, (1, 15, 30), 7.0)  # 7 m/s current (at sea): masked (1)
    got = open_forecast([write_nc(ds, tmp_path / "spiky.nc")])
    counts = masked_counts(got)
    assert counts[cv.WAVE_HS] == 5
    assert counts[cv.WAVE_TM] == 3
    assert counts[cv.WIND_U] == counts[cv.WIND_V] == 1
    assert counts[cv.CURRENT_U] == 1
    assert np.count_nonzero(got[cv.WAVE_HS].values == 27.0) == 4
    assert np.isnan(got[cv.WIND_U].values[0, 0, 0]) and np.isnan(got[cv.WIND_V].values[0, 0, 0])
    assert any(f"5 impossible values of {cv.WAVE_HS}" in s for s in load_notes(got))


def test_the_nws_case_rare_high_values_load(tmp_path: Path) -> None:
    # the real NWS wave GRIB2 had 20 of 1.1 million values above 25 m: it must load
    ds = small_canonical(n_time=2)
    ds[cv.WAVE_HS].values.reshape(-1)[:20] = 26.5
    got = open_forecast([write_nc(ds, tmp_path / "nws.nc")])
    assert np.count_nonzero(got[cv.WAVE_HS].values == 26.5) == 20


def test_a_mostly_impossible_field_refuses_the_file(tmp_path: Path) -> None:
    ds = small_canonical(n_time=2)
    ds[cv.WAVE_HS].values[...] = 9999.0  # an undeclared fill value
    ds[cv.WAVE_HS].values[0, 0, 0] = 2.0
    path = write_nc(ds, tmp_path / "fill.nc")
    with pytest.raises(WeatherError, match=r"fill\.nc.*impossible"):
        open_forecast([path])


def test_text_file_named_nc_is_refused(tmp_path: Path) -> None:
    p = tmp_path / "forecast.nc"
    p.write_text("<html>404 Not Found</html>\n")
    with pytest.raises(WeatherError, match=r"forecast\.nc.*unknown format"):
        open_forecast([p])


def test_netcdf_without_a_recognised_variable_is_refused(tmp_path: Path) -> None:
    ds = small_canonical(n_time=2)
    other = xr.Dataset({"air_temperature": ds[cv.WIND_U].rename("air_temperature")
                        .assign_attrs(units="K", standard_name="air_temperature")})
    p = write_nc(other, tmp_path / "temperature.nc")
    with pytest.raises(WeatherError, match=r"temperature\.nc.*any forecast variable"):
        open_forecast([p])


def test_non_monotonic_coordinates_are_refused(tmp_path: Path) -> None:
    ds = small_canonical(n_time=2)
    lat = ds["latitude"].values.copy()
    lat[[2, 3]] = lat[[3, 2]]  # two rows swapped: not a grid
    bad = ds.assign_coords(latitude=lat)
    with pytest.raises(WeatherError, match=r"shuffled\.nc.*latitude"):
        open_forecast([write_nc(bad, tmp_path / "shuffled.nc")])


def test_grids_that_do_not_meet_are_refused_in_one_cycle(tmp_path: Path) -> None:
    wind = small_canonical(n_time=3, lat=(30.0, 40.0, 0.5), lon=(140.0, 150.0, 0.5))
    far = small_canonical(n_time=3, lat=(-40.0, -30.0, 0.5), lon=(10.0, 20.0, 0.5))
    a = write_nc(wind[[cv.WIND_U, cv.WIND_V]], tmp_path / "wind.nc")
    b = write_nc(far[[cv.CURRENT_U, cv.CURRENT_V]], tmp_path / "currents_far.nc")
    with pytest.raises(WeatherError, match=r"currents_far\.nc.*does not overlap"):
        open_forecast([a, b])


def test_0_360_and_180_frames_combine_on_the_same_places(tmp_path: Path) -> None:
    # wind on a 0..360 grid, currents on a -180..180 grid over the same Atlantic box
    wind = small_canonical(n_time=3, lat=(30.0, 40.0, 1.0), lon=(290.0, 310.0, 1.0))
    cur = small_canonical(n_time=3, lat=(30.0, 40.0, 1.0), lon=(-70.0, -50.0, 1.0))
    lon_c = cur["longitude"].values
    cur[cv.CURRENT_U].values[...] = (lon_c + 70.0)[None, None, :] * 0.05  # 0 at 70 W
    a = write_nc(wind[[cv.WIND_U, cv.WIND_V]], tmp_path / "wind_0_360.nc")
    b = write_nc(cur[[cv.CURRENT_U, cv.CURRENT_V]], tmp_path / "cur_180.nc")
    got = open_forecast([a, b])
    lon = got["longitude"].values
    j = int(np.argmin(np.abs((lon % 360.0) - 300.0)))  # 60 W
    assert float(got[cv.CURRENT_U].values[0, 0, j]) == pytest.approx(0.5, abs=1e-5)
    assert got[cv.CURRENT_U].attrs["source_file"].endswith("cur_180.nc")
    assert got[cv.WIND_U].attrs["source_file"].endswith("wind_0_360.nc")
