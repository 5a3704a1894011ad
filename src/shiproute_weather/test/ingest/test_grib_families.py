"""GRIB families: ECMWF open data (written here with ecCodes from its own GRIB2 sample, as
ECMWF encodes them: centre ecmf, discipline 10 wave parameters), an ensemble with member
numbers, and projected grids from real files (NCEP Eta Lambert conformal 10 m wind; a
polar stereographic grid taken from a real GRIB2)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from shiproute_weather.contract import canonical as cv
from shiproute_weather.contract.record import load_notes
from shiproute_weather.ingest.loaders import open_file, open_forecast
from shiproute_weather.ingest.projected import grid_to_earth, x_axis_bearing_deg
from shiproute_weather.physics.spectral import to_tm01_factor

eccodes = pytest.importorskip("eccodes")
EXAMPLES = Path("/usr/share/doc/python-grib-doc/examples")
needs_examples = pytest.mark.skipif(not (EXAMPLES / "eta.grb").exists(),
                                    reason="Debian package python-grib-doc not installed")


def _message(short: str, value: float | np.ndarray, step: int, number: int | None = None,
             ) -> bytes:
    h = eccodes.codes_grib_new_from_samples("regular_ll_sfc_grib2")
    try:
        eccodes.codes_set(h, "centre", "ecmf")
        for k, v in (("Ni", 9), ("Nj", 5), ("latitudeOfFirstGridPointInDegrees", 44.0),
                     ("latitudeOfLastGridPointInDegrees", 40.0),
                     ("longitudeOfFirstGridPointInDegrees", 340.0),
                     ("longitudeOfLastGridPointInDegrees", 348.0),
                     ("iDirectionIncrementInDegrees", 1.0),
                     ("jDirectionIncrementInDegrees", 1.0)):
            eccodes.codes_set(h, k, v)
        eccodes.codes_set(h, "dataDate", 20260303)
        eccodes.codes_set(h, "dataTime", 0)
        eccodes.codes_set(h, "stepUnits", "h")
        if number is not None:  # an ensemble member (product definition template 4.1)
            eccodes.codes_set(h, "productDefinitionTemplateNumber", 1)
            eccodes.codes_set(h, "typeOfEnsembleForecast", 3 if number else 1)
            eccodes.codes_set(h, "perturbationNumber", number)
            eccodes.codes_set(h, "numberOfForecastsInEnsemble", 4)
        eccodes.codes_set(h, "step", step)
        eccodes.codes_set_string(h, "shortName", short)
        eccodes.codes_set_values(h, np.broadcast_to(value, (45,)).astype(np.float64))
        return bytes(eccodes.codes_get_message(h))
    finally:
        eccodes.codes_release(h)


def test_ecmwf_open_data_grib2_names(tmp_path: Path) -> None:
    values = {"10u": 5.0, "10v": -2.0, "swh": 3.0, "mwd": 250.0, "mwp": 8.0, "shww": 1.5,
              "mdww": 260.0, "mpww": 5.0, "shts": 2.5, "mdts": 240.0, "mpts": 10.0}
    p = tmp_path / "20260303000000-6h-oper-fc.grib2"
    p.write_bytes(b"".join(_message(s, v, step) for step in (0, 3, 6)
                           for s, v in values.items()))
    ds = open_file(p)
    at = {n: float(ds[n].values[1, 2, 4]) for n in cv.present_variables(ds)}
    assert at[cv.WIND_U] == pytest.approx(5.0, abs=0.01)
    assert at[cv.WIND_V] == pytest.approx(-2.0, abs=0.01)
    assert at[cv.WAVE_HS] == pytest.approx(3.0, abs=0.01)
    assert at[cv.WAVE_DIR] == pytest.approx(250.0, abs=0.05)
    assert at[cv.WIND_WAVE_DIR] == pytest.approx(260.0, abs=0.05)
    assert at[cv.SWELL_HS] == pytest.approx(2.5, abs=0.01)
    k = to_tm01_factor("tm_10")  # ECMWF mean periods are Tm-1,0
    assert at[cv.WAVE_TM] == pytest.approx(8.0 * k, abs=0.01)
    assert at[cv.WIND_WAVE_TM] == pytest.approx(5.0 * k, abs=0.01)
    assert at[cv.SWELL_TM] == pytest.approx(10.0 * k, abs=0.01)
    assert ds["longitude"].values[0] == pytest.approx(-20.0)  # 340 E -> 20 W, continuous
    assert ds.sizes["time"] == 3
    assert any("mwp Tm-1,0" in n for n in load_notes(ds))


def test_grib_ensemble_keeps_every_member_by_number(tmp_path: Path) -> None:
    p = tmp_path / "enfo.grib2"
    msgs = []
    for number in range(4):  # control 0 and three perturbed members
        for step in (0, 6):
            msgs.append(_message("10u", 4.0 + number, step, number))
            msgs.append(_message("10v", 0.0, step, number))
            msgs.append(_message("swh", 1.0 + 0.5 * number, step, number))
    p.write_bytes(b"".join(msgs))
    ds = open_forecast([p])
    assert ds[cv.WIND_U].dims == ("member", "time", "latitude", "longitude")
    assert ds.sizes["member"] == 4 and list(ds["member_label"].values) == ["0", "1", "2", "3"]
    assert np.allclose(ds[cv.WIND_U].values[:, 0, 0, 0], [4, 5, 6, 7], atol=0.01)
    assert np.allclose(ds[cv.WAVE_HS].values[:, 1, 0, 0], [1.0, 1.5, 2.0, 2.5], atol=0.01)
    assert ds.attrs["member_kind"] == "ensemble" and "4 members kept" in ds.attrs["ensemble"]


@needs_examples
def test_eta_lambert_conformal_wind_regridded_and_turned_to_east_north() -> None:
    ds = open_file(EXAMPLES / "eta.grb")
    assert {cv.WIND_U, cv.WIND_V} <= set(ds.data_vars)
    lat, lon = ds["latitude"].values, ds["longitude"].values
    assert lat[0] >= 12.0 and lat[-1] <= 62.0 and lon[0] < -120.0 < -60.0 < lon[-1]
    assert any("Lambert conformal" in n and "east/north" in n for n in load_notes(ds))
    speed = np.hypot(ds[cv.WIND_U].values, ds[cv.WIND_V].values)
    assert 0.5 < np.nanmean(speed) < 15.0 and np.nanmax(speed) < 40.0


@needs_examples
def test_lambert_grid_axis_bearing_matches_snyder_convergence() -> None:
    with (EXAMPLES / "eta.grb").open("rb") as f:
        while True:
            h = eccodes.codes_grib_new_from_file(f)
            if eccodes.codes_get(h, "shortName") == "10u":
                break
            eccodes.codes_release(h)
    shape = (eccodes.codes_get(h, "Ny"), eccodes.codes_get(h, "Nx"))
    lat2 = eccodes.codes_get_array(h, "latitudes").reshape(shape)
    lon2 = eccodes.codes_get_array(h, "longitudes").reshape(shape)
    assert eccodes.codes_get(h, "Latin1InDegrees") == 25.0
    assert eccodes.codes_get(h, "LoVInDegrees") == 265.0
    eccodes.codes_release(h)
    # tangent Lambert conformal at 25 N, central meridian 265 E (the file's Latin1/LoV):
    # the grid's y axis is turned n (lon - lon0) east of true north (Snyder 1987, 15-1a)
    n = np.sin(np.deg2rad(25.0))
    expected = 90.0 + n * (((lon2 - 265.0) + 180.0) % 360.0 - 180.0)
    got = x_axis_bearing_deg(lat2, lon2)
    assert np.max(np.abs(got - expected)[2:-2, 2:-2]) < 0.2


def test_grid_to_earth_is_a_rotation() -> None:
    u, v = np.array([3.0, -1.0]), np.array([4.0, 2.0])
    e, n = grid_to_earth(u, v, np.array([90.0, 90.0]))  # grid aligned with east/north
    assert np.allclose(e, u) and np.allclose(n, v)
    e, n = grid_to_earth(u, v, np.array([180.0, 30.0]))  # x axis pointing south / NNE
    assert np.allclose(np.hypot(e, n), np.hypot(u, v))
    assert e[0] == pytest.approx(v[0]) and n[0] == pytest.approx(-u[0])


@needs_examples
def test_polar_stereographic_grid_from_a_real_file(tmp_path: Path) -> None:
    from pyproj import Proj

    # the geometry of the real South-African polar stereographic GRIB2 (60 S true scale)
    src = EXAMPLES / "safrica.grib2"
    with src.open("rb") as f:
        h = eccodes.codes_grib_new_from_file(f)
    lats = eccodes.codes_get_array(h, "latitudes")
    lons = eccodes.codes_get_array(h, "longitudes")
    lov = eccodes.codes_get(h, "orientationOfTheGridInDegrees")
    lad = eccodes.codes_get(h, "LaDInDegrees")
    # a uniform 10 m/s westerly, written as grid-relative components with the meridian
    # convergence that pyproj computes for this projection
    proj = Proj(f"+proj=stere +lat_0=-90 +lat_ts={lad} +lon_0={lov} +R=6371229")
    gamma = np.deg2rad(proj.get_factors(lons, lats).meridian_convergence)
    ue, ve = 10.0, 0.0
    ug = ue * np.cos(gamma) - ve * np.sin(gamma)
    vg = ue * np.sin(gamma) + ve * np.cos(gamma)
    out = tmp_path / "ps_wind.grib2"
    msgs = []
    for short, vals in (("10u", ug), ("10v", vg)):
        c = eccodes.codes_clone(h)
        eccodes.codes_set(c, "discipline", 0)
        eccodes.codes_set(c, "parameterCategory", 2)
        eccodes.codes_set(c, "parameterNumber", 2 if short == "10u" else 3)
        eccodes.codes_set(c, "typeOfFirstFixedSurface", 103)
        eccodes.codes_set(c, "scaledValueOfFirstFixedSurface", 10)
        eccodes.codes_set(c, "resolutionAndComponentFlags", 8)  # u/v relative to the grid
        eccodes.codes_set(c, "packingType", "grid_simple")
        eccodes.codes_set(c, "bitsPerValue", 16)
        eccodes.codes_set_values(c, vals)
        msgs.append(bytes(eccodes.codes_get_message(c)))
        eccodes.codes_release(c)
    eccodes.codes_release(h)
    out.write_bytes(b"".join(msgs))
    ds = open_file(out)
    assert any("polar stereographic" in n for n in load_notes(ds))
    e, n = ds[cv.WIND_U].values, ds[cv.WIND_V].values
    ok = np.isfinite(e)
    assert ok.mean() > 0.3
    assert np.allclose(e[ok], 10.0, atol=0.15) and np.allclose(n[ok], 0.0, atol=0.15)
