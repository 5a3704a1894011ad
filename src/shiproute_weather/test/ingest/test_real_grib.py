"""Real forecast files from Debian python-grib-doc through the library."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from shiproute_weather.contract import canonical as cv
from shiproute_weather.ingest.loaders import open_file, open_forecast
from shiproute_weather.sampling.sampler import ForecastSampler

EXAMPLES = Path("/usr/share/doc/python-grib-doc/examples")
pytestmark = pytest.mark.skipif(
    not (EXAMPLES / "ecmwf_tigge.grb").exists(),
    reason="Debian package python-grib-doc not installed (apt-get install python-grib-doc)")


def test_ecmwf_tigge_reduced_gaussian_wind() -> None:
    ds = open_file(EXAMPLES / "ecmwf_tigge.grb")
    assert set(ds.data_vars) == {cv.WIND_U, cv.WIND_V}
    # reduced Gaussian N200 -> 400 rows, regridded onto the densest row (800 columns)
    assert ds.sizes["latitude"] == 400 and ds.sizes["longitude"] == 800
    assert str(ds.time.values[0])[:16] == "2007-05-10T00:00"  # valid = 2007-05-05 + 120 h
    assert ds.attrs["forecast_reference_time"] == "2007-05-05T00:00:00Z"
    speed = np.hypot(ds[cv.WIND_U], ds[cv.WIND_V])
    assert 4.0 < float(speed.mean()) < 10.0  # global mean 10 m wind speed is ~7 m/s
    assert float(speed.max()) < 40.0
    # trades: easterly on average between 10 and 20 N over the open Pacific
    trades = ds[cv.WIND_U].sel(latitude=slice(10, 20), longitude=slice(180, 230)).mean()
    assert float(trades) < -2.0


def test_gfs_2p5deg_multi_field_messages() -> None:
    ds = open_file(EXAMPLES / "gfs.t12z.pgrbf120.2p5deg.grib2")
    assert set(ds.data_vars) == {cv.WIND_U, cv.WIND_V}  # u and v share one GRIB message
    assert ds.sizes["latitude"] == 73 and ds.sizes["longitude"] == 144
    assert float(ds.latitude[0]) == -90.0 and float(ds.longitude[1]) == 2.5
    assert str(ds.time.values[0])[:13] == "2011-01-15T12"
    assert float(np.hypot(ds[cv.WIND_U], ds[cv.WIND_V]).max()) < 40.0


def test_ecmwf_wave_height_reduced_latlon_land_is_nan() -> None:
    ds = open_forecast([EXAMPLES / "reduced_latlon_surface.grib2"])
    hs = ds[cv.WAVE_HS]
    assert list(ds.data_vars) == [cv.WAVE_HS]
    assert float(hs.min()) >= 0.0 and float(hs.max()) < 20.0
    s = ForecastSampler(ds)
    t = float(ds.time.values[0].astype("datetime64[s]").astype(np.int64))
    got = s.sample(np.array([10.0, 260.0, 200.0]), np.array([20.0, 40.0, 40.0]),
                   np.array([t, t, t]))[cv.WAVE_HS]
    assert np.isnan(got[0]) and np.isnan(got[1])  # Sahara, central USA: land
    assert 0.5 < got[2] < 15.0  # North Pacific in February


def test_truncated_grib_is_reported_with_its_name(tmp_path: Path) -> None:
    from shiproute_weather.errors import ForecastFileError

    cut = tmp_path / "cut.grib2"
    cut.write_bytes((EXAMPLES / "gfs.t12z.pgrbf120.2p5deg.grib2").read_bytes()[:20000])
    with pytest.raises(ForecastFileError, match=r"cut\.grib2"):
        open_forecast([cut])


def test_real_gfs_wind_only_grib2_gets_waves_estimated_or_is_refused() -> None:
    from shiproute_weather.contract.record import load_notes
    from shiproute_weather.errors import MissingVariableError

    path = EXAMPLES / "gfs.t12z.pgrbf120.2p5deg.grib2"  # real NCEP GFS: 10 m wind, no waves
    ds = open_forecast([path])
    assert any(n.startswith("waves estimated from wind") for n in load_notes(ds))
    hs = ds[cv.WAVE_HS].values
    speed = np.hypot(ds[cv.WIND_U].values, ds[cv.WIND_V].values)
    sea = np.isfinite(hs)
    # no sea exceeds the fully developed Pierson-Moskowitz height of its own wind (+ the
    # growth from a stronger wind earlier is impossible here: one valid time, 24 h spin-up)
    assert np.all(hs[sea] <= 0.241 * np.maximum(speed[sea], 0.5) ** 2 / 9.81 + 1e-3)
    assert 0.5 < float(np.nanmean(hs)) < 5.0  # global mean Hs is ~2.5 m
    assert 0.2 < sea.mean() < 0.9  # land is NaN
    with pytest.raises(MissingVariableError, match=r"pgrbf120\.2p5deg\.grib2"):
        open_forecast([path], waves_from_wind=False)
