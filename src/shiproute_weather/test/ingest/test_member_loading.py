"""Loaders keep every member: GRIB2 ensembles (template 4.1), NetCDF `realization`, several
deterministic files as a multi-model cycle; refusals name the input."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from member_fixtures import GFS, ensemble_grib2, realization_netcdf
from shiproute_weather.contract import canonical as cv
from shiproute_weather.contract.members import member_count, member_labels
from shiproute_weather.contract.record import load_notes
from shiproute_weather.errors import GridError
from shiproute_weather.ingest.loaders import open_file, open_forecast
from shiproute_weather.ingest.members import open_members
from weather_fixtures import small_canonical, write_nc

eccodes = pytest.importorskip("eccodes")
needs_examples = pytest.mark.skipif(not GFS.exists(), reason="Debian python-grib-doc missing")


@needs_examples
def test_grib2_ensemble_keeps_every_member_and_its_wind(tmp_path: Path) -> None:
    # control + 2 perturbed: cfgrib reads the control (scalar number) and the perturbed
    # members (number 1..2) as separate hypercubes; all three must be kept
    path = ensemble_grib2(tmp_path / "gefs.grib2", [0.0, 3.0, -2.0])
    real = open_file(GFS)
    ds = open_file(path)
    assert member_count(ds) == 3 and member_labels(ds) == ("0", "1", "2")
    assert str(ds["time"].values[0])[:13] == str(real["time"].values[0])[:13]
    assert ds.attrs["member_kind"] == "ensemble"
    u = ds[cv.WIND_U].values
    # GFS packs 10 m wind to 0.01 m/s or finer (decimal scale); re-encoding keeps that step
    np.testing.assert_allclose(u[0], real[cv.WIND_U].values, atol=0.011)
    np.testing.assert_allclose(u[1] - u[0], 3.0, atol=0.022)
    np.testing.assert_allclose(u[2] - u[0], -2.0, atol=0.022)
    np.testing.assert_allclose(ds[cv.WIND_V].values[1], ds[cv.WIND_V].values[0], atol=0.011)
    assert any("3 members kept" in n for n in load_notes(ds))


def test_two_member_netcdf_realization_keeps_both_winds(tmp_path: Path) -> None:
    base = small_canonical(n_time=3)
    path = realization_netcdf(base, tmp_path / "ens.nc", [0.0, -2.5])
    ds = open_forecast([path])
    assert member_count(ds) == 2 and member_labels(ds) == ("0", "1")
    u = ds[cv.WIND_U].values
    np.testing.assert_array_equal(u[0], base[cv.WIND_U].values)
    np.testing.assert_allclose(u[1] - u[0], -2.5, atol=1e-5)
    np.testing.assert_array_equal(ds[cv.WAVE_HS].values[0], ds[cv.WAVE_HS].values[1])
    # the node streams a realization file member by member (test_member_stream.py)
    from shiproute_weather.ingest.cycle_builder import CycleConfig
    from shiproute_weather.ingest.stream import streamable
    assert streamable([str(path)], CycleConfig())


def test_netcdf_with_duplicate_member_numbers_is_refused(tmp_path: Path) -> None:
    import xarray as xr

    path = realization_netcdf(small_canonical(n_time=2), tmp_path / "dup.nc", [0.0, 1.0])
    raw = xr.load_dataset(path)
    raw = raw.assign_coords(realization=np.array([4, 4], dtype=np.int32))
    raw.to_netcdf(tmp_path / "dup2.nc")
    with pytest.raises(GridError, match=r"dup2\.nc.*member labels \['4'\] appear more than"):
        open_forecast([tmp_path / "dup2.nc"])


def test_multi_model_members_are_regridded_with_labels_and_provenance(tmp_path: Path) -> None:
    gfs = small_canonical(n_time=5)
    ecmwf = small_canonical(n_time=3, lat=(28.0, 42.0, 1.0), lon=(165.0, 200.0, 1.0), seed=5)
    ecmwf.attrs["source"] = "ECMWF"
    ecmwf = ecmwf.isel(time=[0, 2])  # 6-hourly
    a = write_nc(gfs, tmp_path / "gfs.nc")
    b = write_nc(ecmwf, tmp_path / "ecmwf.nc")
    ds = open_members([[a], [b]])
    assert member_labels(ds) == ("unit-test", "ecmwf")
    assert ds.attrs["member_kind"] == "multi-model"
    assert ds.sizes["latitude"] == gfs.sizes["latitude"] and ds.sizes["time"] == 5
    np.testing.assert_array_equal(ds[cv.WIND_U].values[0], open_forecast([a])[cv.WIND_U].values)
    # member 1 at a shared node and valid time equals the ECMWF file there
    got = float(ds[cv.WIND_U].sel(latitude=32.0, longitude=170.0).values[1, 0])
    assert got == pytest.approx(float(ecmwf[cv.WIND_U].sel(latitude=32.0, longitude=170.0)
                                      .values[0]), abs=1e-4)
    src = ds[cv.WIND_U].attrs["source_file"]
    assert "unit-test: " in src and str(a) in src and str(b) in src
    assert str(a) in ds.attrs["member_sources"] and str(b) in ds.attrs["member_sources"]
    assert "regridded" in ds[cv.WIND_U].attrs["conversion"]
    named = open_members([[a], [b]], labels=["gfs", "ecmwf"])
    assert member_labels(named) == ("gfs", "ecmwf")


def test_members_whose_grids_or_times_do_not_meet_are_refused(tmp_path: Path) -> None:
    a = write_nc(small_canonical(n_time=3), tmp_path / "pacific.nc")
    far = small_canonical(n_time=3, lat=(-40.0, -30.0, 0.5), lon=(10.0, 30.0, 0.5))
    b = write_nc(far, tmp_path / "south_atlantic.nc")
    with pytest.raises(GridError, match=r"south_atlantic\.nc.*does not overlap"):
        open_members([[a], [b]])
    later = small_canonical(n_time=3, ref="2026-03-09T12:00:00")  # six days on
    c = write_nc(later, tmp_path / "next_week.nc")
    with pytest.raises(GridError, match=r"next_week\.nc: its valid times .* do not overlap"):
        open_members([[a], [c]])


def test_member_count_mismatch_between_files_is_refused(tmp_path: Path) -> None:
    base = small_canonical(n_time=3)
    wind = realization_netcdf(base[[cv.WIND_U, cv.WIND_V]], tmp_path / "wind3.nc", [0, 1, 2])
    waves = realization_netcdf(base[[cv.WAVE_HS, cv.WIND_U, cv.WIND_V]], tmp_path / "hs2.nc",
                               [0, 1])
    with pytest.raises(GridError, match=r"member count mismatch"):
        open_forecast([wind, waves])
