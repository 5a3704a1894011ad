"""Each provider naming convention loads with canonical names, SI units and directions."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from shiproute_core.units import M_S_PER_KNOT
from shiproute_weather.contract import canonical as cv
from shiproute_weather.ingest.loaders import open_file, open_forecast
from shiproute_weather.physics.spectral import to_tm01_factor

KN = M_S_PER_KNOT
TIMES = np.datetime64("2026-03-03T12:00", "ns") + np.arange(3) * np.timedelta64(6, "h")


def _raw(names: dict[str, tuple[float, str]], lat: np.ndarray, lon: np.ndarray,
         lat_name: str = "latitude", lon_name: str = "longitude", time_name: str = "time",
         extra_dim: tuple[str, np.ndarray] | None = None) -> xr.Dataset:
    """Constant fields (value, units) on a grid; optional leading extra dim (depth...)."""
    dims = [time_name, lat_name, lon_name]
    shape = [TIMES.size, lat.size, lon.size]
    coords = {time_name: TIMES, lat_name: lat, lon_name: lon}
    if extra_dim is not None:
        dims.insert(1, extra_dim[0])
        shape.insert(1, extra_dim[1].size)
        coords[extra_dim[0]] = extra_dim[1]
    data = {n: (dims, np.full(shape, v, np.float32), {"units": u} if u else {})
            for n, (v, u) in names.items()}
    return xr.Dataset(data, coords=coords)


def _write(ds: xr.Dataset, path: Path) -> Path:
    ds.to_netcdf(path)
    return path


def test_ecmwf_era5_names_periods_and_lon_0_360(tmp_path: Path) -> None:
    lat = np.arange(60.0, 29.0, -1.0)  # descending, as ECMWF writes it
    lon = np.arange(0.0, 360.0, 1.0)
    raw = _raw({"u10": (3.0, "m s**-1"), "v10": (-4.0, "m s**-1"), "swh": (2.5, "m"),
                "mwd": (270.0, "Degree true"), "mwp": (8.0, "s"), "pp1d": (10.0, "s"),
                "shww": (1.5, "m"), "mdww": (280.0, "Degree true"), "mpww": (5.0, "s"),
                "shts": (2.0, "m"), "mdts": (300.0, "Degree true"), "mpts": (11.0, "s")},
               lat, lon, time_name="valid_time")
    ds = open_forecast([_write(raw, tmp_path / "era5.nc")])
    assert np.all(np.diff(ds.latitude.values) > 0)
    assert ds.longitude.values[0] == 0.0 and ds.longitude.values[-1] == 359.0
    pick = ds.isel(time=1, latitude=3, longitude=200)
    assert float(pick[cv.WIND_U]) == 3.0 and float(pick[cv.WIND_V]) == -4.0
    assert float(pick[cv.WAVE_DIR]) == 270.0
    # mwp is the energy period Tm-1,0 -> converted to Tm01 (pp1d ignored when mwp exists)
    assert float(pick[cv.WAVE_TM]) == pytest.approx(8.0 * to_tm01_factor("tm_10"), rel=1e-6)
    assert float(pick[cv.SWELL_HS]) == 2.0 and float(pick[cv.SWELL_DIR]) == 300.0
    assert float(pick[cv.WIND_WAVE_TM]) == pytest.approx(5.0 * to_tm01_factor("tm_10"), 1e-6)


def test_gfs_nomads_names_and_units(tmp_path: Path) -> None:
    raw = _raw({"ugrd10m": (10.0, "m/s"), "vgrd10m": (-2.0, "m/s")},
               np.arange(90.0, -91.0, -2.5), np.arange(0.0, 360.0, 2.5), "lat", "lon")
    ds = open_file(_write(raw, tmp_path / "gfs.nc"))
    assert set(ds.data_vars) == {cv.WIND_U, cv.WIND_V}  # the file's own fields
    assert ds.latitude.values[0] == -90.0
    assert float(ds[cv.WIND_U].max()) == 10.0 and float(ds[cv.WIND_V].min()) == -2.0


def test_wavewatch3_names_and_peak_period(tmp_path: Path) -> None:
    raw = _raw({"HTSGW": (3.0, "m"), "DIRPW": (250.0, "deg"), "PERPW": (12.0, "s"),
                "WVHGT": (1.0, "m"), "WVDIR": (240.0, "deg"), "WVPER": (4.0, "s"),
                "SWELL": (2.8, "m"), "SWDIR": (255.0, "deg"), "SWPER": (11.0, "s"),
                "UGRD": (-20.0, "knots"), "VGRD": (0.0, "knots")},
               np.arange(10.0, 20.1, 0.5), np.arange(-180.0, -150.0, 0.5))
    ds = open_forecast([_write(raw, tmp_path / "ww3.nc")])
    # a region west of 180 keeps -180..180 longitudes
    assert ds.longitude.values[0] == -180.0
    assert float(ds[cv.WAVE_TM].max()) == pytest.approx(12.0 * to_tm01_factor("tp"), rel=1e-6)
    assert float(ds[cv.WIND_U].min()) == pytest.approx(-20.0 * KN, rel=1e-6)
    assert float(ds[cv.SWELL_TM].max()) == 11.0 and float(ds[cv.WIND_WAVE_DIR].max()) == 240.0


def test_copernicus_marine_across_antimeridian_and_depth(tmp_path: Path) -> None:
    lon = np.concatenate([np.arange(160.0, 180.0, 0.25), np.arange(-180.0, -160.0, 0.25)])
    waves = _raw({"VHM0": (4.0, "m"), "VMDR": (10.0, "degree"), "VTM10": (9.0, "s"),
                  "VTPK": (11.0, "s"), "VHM0_WW": (2.0, "m"), "VMDR_WW": (20.0, "degree"),
                  "VTM01_WW": (5.0, "s"), "VHM0_SW1": (3.0, "m"), "VMDR_SW1": (350.0, "degree"),
                  "VTM01_SW1": (12.0, "s")}, np.arange(30.0, 40.01, 0.25), lon)
    cur = _raw({"uo": (0.1, "m s-1"), "vo": (0.2, "m s-1"), "utotal": (0.5, "m s-1"),
                "vtotal": (-0.5, "m s-1")}, np.arange(30.0, 40.01, 1 / 12), lon[::3] % 360,
               extra_dim=("depth", np.array([0.494, 1.54])))
    wind = _raw({"eastward_wind": (5.0, "m s-1"), "northward_wind": (1.0, "m s-1")},
                np.arange(25.0, 45.01, 0.5), np.arange(150.0, 210.01, 0.5))
    ds = open_forecast([_write(waves, tmp_path / "w.nc"), _write(cur, tmp_path / "c.nc"),
                        _write(wind, tmp_path / "u.nc")])
    # combined on the wind grid (first file with wind), continuous past 180
    assert ds.longitude.values[0] == 150.0 and ds.longitude.values[-1] == 210.0
    inside = ds.sel(latitude=35.0, longitude=[170.0, 185.0]).isel(time=1)
    np.testing.assert_allclose(inside[cv.WAVE_HS], 4.0, rtol=1e-6)
    np.testing.assert_allclose(inside[cv.SWELL_DIR], 350.0, atol=1e-3)
    np.testing.assert_allclose(inside[cv.WAVE_TM], 9.0 * to_tm01_factor("tm_10"), rtol=1e-5)
    # total velocity (incl. tides/Stokes) preferred over the Eulerian uo/vo
    np.testing.assert_allclose(inside[cv.CURRENT_U], 0.5, rtol=1e-5)
    np.testing.assert_allclose(inside[cv.CURRENT_V], -0.5, rtol=1e-5)
    # outside the wave model's region there is no value (NaN), not zero
    assert np.isnan(float(ds[cv.WAVE_HS].sel(latitude=35.0, longitude=150.0).isel(time=0)))


def test_cf_standard_names_to_direction_and_unit_conversions(tmp_path: Path) -> None:
    raw = _raw({"a": (20.0, "kt"), "b": (0.0, "kt"), "c": (3.0, "m"), "d": (90.0, "degree"),
                "e": (50.0, "cm/s"), "f": (0.0, "cm s-1"), "g": (30.0, "m s-1"),
                "h": (45.0, "degree")},
               np.arange(0.0, 5.1, 1.0), np.arange(100.0, 105.1, 1.0))
    std = {"a": "eastward_wind", "b": "northward_wind",
           "c": "sea_surface_wave_significant_height", "d": "sea_surface_wave_to_direction",
           "e": "surface_eastward_sea_water_velocity",
           "f": "surface_northward_sea_water_velocity"}
    for k, s in std.items():
        raw[k].attrs["standard_name"] = s
    ds = open_forecast([_write(raw.drop_vars(["g", "h"]), tmp_path / "cf.nc")])
    assert float(ds[cv.WIND_U].max()) == pytest.approx(20 * KN, rel=1e-6)
    assert float(ds[cv.WAVE_DIR].max()) == 270.0  # going to 90 = coming from 270
    assert float(ds[cv.CURRENT_U].max()) == pytest.approx(0.5, rel=1e-6)
    # wind given as speed + from-direction becomes u/v ("going to" components)
    sd = raw[["g", "h", "c"]].rename({"g": "wind_speed_10m", "h": "dir10"})
    sd["wind_speed_10m"].attrs["standard_name"] = "wind_speed"
    sd["dir10"].attrs["standard_name"] = "wind_from_direction"
    ds2 = open_forecast([_write(sd, tmp_path / "sd.nc")])
    u = float(ds2[cv.WIND_U].max())
    v = float(ds2[cv.WIND_V].max())
    assert u == pytest.approx(-30 / np.sqrt(2), rel=1e-5)  # from NE -> blowing to SW
    assert v == pytest.approx(-30 / np.sqrt(2), rel=1e-5)
