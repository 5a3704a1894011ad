"""Each provider's naming family loads into the canonical dataset with SI units and the
conventions (wind and waves "coming from", currents "going to"). The files are written here
with netCDF4 in the structure the providers serve them: dimension and variable names,
attributes, int16 packing with scale/offset and fill values, descending latitudes, 0..360
longitudes, extra level dimensions."""

from __future__ import annotations

from pathlib import Path

import netCDF4
import numpy as np
import pytest
from shiproute_weather.contract import canonical as cv
from shiproute_weather.contract.record import load_notes
from shiproute_weather.ingest.loaders import open_file, open_forecast
from shiproute_weather.physics.spectral import to_tm01_factor

LAT = np.array([45.0, 44.0, 43.0, 42.0])  # providers serve north -> south
LON = np.array([300.0, 301.0, 302.0, 303.0, 304.0])  # 0..360 frame (60 W .. 56 W)
HOURS = np.array([0.0, 3.0, 6.0])


def _nc(path: Path, time_name: str = "time", time_units: str = "hours since 2026-03-03 00:00:00",
        lat_name: str = "latitude", lon_name: str = "longitude",
        extra_dims: dict[str, tuple[np.ndarray, dict]] | None = None) -> netCDF4.Dataset:
    ds = netCDF4.Dataset(path, "w", format="NETCDF4")
    ds.createDimension(time_name, None)
    for name, (values, attrs) in (extra_dims or {}).items():
        ds.createDimension(name, values.size)
        v = ds.createVariable(name, "f4", (name,))
        v[:] = values
        v.setncatts(attrs)
    ds.createDimension(lat_name, LAT.size)
    ds.createDimension(lon_name, LON.size)
    t = ds.createVariable(time_name, "f8", (time_name,))
    t.units, t.standard_name, t.calendar = time_units, "time", "proleptic_gregorian"
    t[:] = HOURS
    la = ds.createVariable(lat_name, "f4", (lat_name,))
    la.units, la.standard_name = "degrees_north", "latitude"
    la[:] = LAT
    lo = ds.createVariable(lon_name, "f4", (lon_name,))
    lo.units, lo.standard_name = "degrees_east", "longitude"
    lo[:] = LON
    return ds


def _field(shape: tuple[int, ...], value: float) -> np.ndarray:
    return np.full(shape, value, dtype=np.float64)


def _packed(ds: netCDF4.Dataset, name: str, dims: tuple[str, ...], values: np.ndarray,
            attrs: dict, scale: float = 0.01, offset: float = 0.0) -> None:
    """An int16 variable with scale_factor/add_offset and a fill value, as ERA5/WW3 store."""
    v = ds.createVariable(name, "i2", dims, fill_value=np.int16(-32767))
    v.setncatts({"scale_factor": scale, "add_offset": offset, **attrs})
    v[:] = values  # netCDF4 packs with the scale/offset on write


def _float(ds: netCDF4.Dataset, name: str, dims: tuple[str, ...], values: np.ndarray,
           attrs: dict) -> None:
    v = ds.createVariable(name, "f4", dims, fill_value=np.float32(np.nan))
    v.setncatts(attrs)
    v[:] = values


def test_gfs_thredds_ncss_wind_takes_the_10_m_level(tmp_path: Path) -> None:
    heights = np.array([10.0, 20.0, 30.0, 40.0, 50.0, 80.0, 100.0])
    p = tmp_path / "GFS_Global_0p25deg_ncss.nc"
    ds = _nc(p, time_units="Hour since 2026-03-03T00:00:00Z", lat_name="latitude",
             extra_dims={"height_above_ground1": (heights, {
                 "units": "m", "long_name": "Specified height level above ground",
                 "positive": "up", "datum": "ground", "_CoordinateAxisType": "Height",
                 "_CoordinateZisPositive": "up"})})
    shape = (HOURS.size, heights.size, LAT.size, LON.size)
    # each level carries a different wind so a wrong pick shows
    u = np.broadcast_to(heights[None, :, None, None] * 0.5, shape)  # 5 m/s at 10 m
    v = np.broadcast_to(-heights[None, :, None, None] * 0.2, shape)  # -2 m/s at 10 m
    dims = ("time", "height_above_ground1", "latitude", "longitude")
    common = {"units": "m/s", "abbreviation": "UGRD", "grid_mapping": "LatLon_Projection",
              "coordinates": "reftime time height_above_ground1 latitude longitude",
              "Grib_Variable_Id": "VAR_0-2-2_L103", "Grib2_Parameter_Category": "Momentum"}
    _float(ds, "u-component_of_wind_height_above_ground", dims, u,
           common | {"long_name": "u-component of wind @ Specified height level above ground",
                     "Grib2_Parameter": np.array([0, 2, 2], dtype=np.int32)})
    _float(ds, "v-component_of_wind_height_above_ground", dims, v,
           common | {"long_name": "v-component of wind @ Specified height level above ground",
                     "abbreviation": "VGRD"})
    _float(ds, "Temperature_surface", ("time", "latitude", "longitude"),
           _field((HOURS.size, LAT.size, LON.size), 280.0), {"units": "K"})
    proj = ds.createVariable("LatLon_Projection", "i4")
    proj.grid_mapping_name = "latitude_longitude"
    ref = ds.createVariable("reftime", "f8")
    ref.units, ref.standard_name = "Hour since 2026-03-03T00:00:00Z", "forecast_reference_time"
    ref.assignValue(0.0)
    ds.Originating_or_generating_Center = "US National Weather Service, NCEP"
    ds.close()
    got = open_file(p)
    assert float(got[cv.WIND_U].max()) == pytest.approx(5.0)
    assert float(got[cv.WIND_V].min()) == pytest.approx(-2.0)
    assert got[cv.WIND_U].attrs["source_variable"] == "u-component_of_wind_height_above_ground"
    assert list(got["latitude"].values) == sorted(LAT)  # south -> north
    assert got["longitude"].values[0] == pytest.approx(-60.0)  # a region west of 180


def test_era5_netcdf_packed_int16_with_valid_time(tmp_path: Path) -> None:
    p = tmp_path / "era5.nc"
    ds = _nc(p, time_name="valid_time", time_units="seconds since 1970-01-01")
    ds["valid_time"][:] = (np.datetime64("2026-03-03T00:00", "s").astype(np.int64)
                           + HOURS * 3600)
    shape = (HOURS.size, LAT.size, LON.size)
    dims = ("valid_time", "latitude", "longitude")
    _packed(ds, "u10", dims, _field(shape, -3.0), {"units": "m s**-1",
                                                   "long_name": "10 metre U wind component"})
    _packed(ds, "v10", dims, _field(shape, 4.0), {"units": "m s**-1"})
    _packed(ds, "swh", dims, _field(shape, 2.5),
            {"units": "m", "long_name": "Significant height of combined wind waves and swell"})
    _packed(ds, "mwd", dims, _field(shape, 270.0), {"units": "degree true"}, scale=0.01,
            offset=180.0)
    _packed(ds, "mwp", dims, _field(shape, 8.0), {"units": "s"})
    ds.close()
    got = open_file(p)
    assert float(got[cv.WIND_U][0, 0, 0]) == pytest.approx(-3.0, abs=0.006)
    assert float(got[cv.WAVE_HS][0, 0, 0]) == pytest.approx(2.5, abs=0.006)
    assert float(got[cv.WAVE_DIR][0, 0, 0]) == pytest.approx(270.0, abs=0.006)
    # ECMWF mwp is the energy period Tm-1,0: converted to Tm01 and stated
    assert float(got[cv.WAVE_TM][0, 0, 0]) == pytest.approx(8.0 * to_tm01_factor("tm_10"),
                                                            abs=0.01)
    assert any("mwp Tm-1,0" in n for n in load_notes(got))


def test_cmems_waves_peak_period_converted_and_stated(tmp_path: Path) -> None:
    p = tmp_path / "cmems_mod_glo_wav_anfc_0.083deg_PT3H-i.nc"
    ds = _nc(p, time_units="hours since 1950-01-01")
    ds["time"][:] = (np.datetime64("2026-03-03T00", "h") - np.datetime64("1950-01-01T00", "h")
                     ).astype(np.int64) + HOURS
    shape = (HOURS.size, LAT.size, LON.size)
    dims = ("time", "latitude", "longitude")
    for name, val, units, std in (
            ("VHM0", 3.0, "m", "sea_surface_wave_significant_height"),
            ("VMDR", 45.0, "degree", "sea_surface_wave_from_direction"),
            ("VTPK", 10.0, "s",
             "sea_surface_wave_period_at_variance_spectral_density_maximum"),
            ("VHM0_WW", 1.0, "m", "sea_surface_wind_wave_significant_height"),
            ("VMDR_WW", 90.0, "degree", "sea_surface_wind_wave_from_direction"),
            ("VTM01_WW", 4.0, "s", "sea_surface_wind_wave_mean_period"),
            ("VHM0_SW1", 2.8, "m", "sea_surface_primary_swell_wave_significant_height"),
            ("VMDR_SW1", 30.0, "degree", "sea_surface_primary_swell_wave_from_direction"),
            ("VTM01_SW1", 11.0, "s", "sea_surface_primary_swell_wave_mean_period")):
        _float(ds, name, dims, _field(shape, val), {"units": units, "standard_name": std})
    ds.close()
    got = open_file(p)
    assert float(got[cv.WAVE_TM][0, 0, 0]) == pytest.approx(10.0 * to_tm01_factor("tp"),
                                                            rel=1e-5)
    g = 3.3  # DNV-RP-C205 (2010) 3.5.5.4: T1/Tp of a JONSWAP spectrum
    assert to_tm01_factor("tp") == pytest.approx(
        0.7303 + 0.04936 * g - 0.006556 * g**2 + 0.0003610 * g**3, abs=0.002)
    assert any("VTPK peak period Tp" in n for n in load_notes(got))
    assert float(got[cv.SWELL_HS][0, 0, 0]) == pytest.approx(2.8)
    assert float(got[cv.WIND_WAVE_DIR][0, 0, 0]) == pytest.approx(90.0)
    # VTM10 wins over VTPK (the energy period converts with less spectral-shape error)
    p2 = tmp_path / "with_vtm10.nc"
    ds = _nc(p2)
    _float(ds, "VHM0", dims, _field(shape, 3.0), {"units": "m"})
    _float(ds, "VTPK", dims, _field(shape, 10.0), {"units": "s"})
    _float(ds, "VTM10", dims, _field(shape, 8.0), {"units": "s"})
    _float(ds, "VTM02", dims, _field(shape, 7.0), {"units": "s"})
    ds.close()
    got = open_file(p2)
    assert got[cv.WAVE_TM].attrs["source_variable"] == "VTM10"


def test_cmems_physics_currents_going_to_with_depth(tmp_path: Path) -> None:
    p = tmp_path / "cmems_mod_glo_phy_anfc_0.083deg_PT1H-m.nc"
    depth = np.array([0.494025, 1.541375])
    ds = _nc(p, extra_dims={"depth": (depth, {"units": "m", "positive": "down",
                                              "standard_name": "depth"})})
    shape = (HOURS.size, depth.size, LAT.size, LON.size)
    dims = ("time", "depth", "latitude", "longitude")
    uo = np.broadcast_to(np.array([1.2, 0.3])[None, :, None, None], shape)
    _float(ds, "uo", dims, uo, {"units": "m s-1",
                                "standard_name": "eastward_sea_water_velocity"})
    _float(ds, "vo", dims, np.zeros(shape), {"units": "m s-1",
                                             "standard_name": "northward_sea_water_velocity"})
    ds.close()
    got = open_file(p)
    assert float(got[cv.CURRENT_U][0, 0, 0]) == pytest.approx(1.2)  # the surface layer
    assert got[cv.CURRENT_U].attrs["direction_convention"] == "going_to"
    # the merged product: total currents (tides, Stokes drift) win over Eulerian uo/vo
    p2 = tmp_path / "cmems_mod_glo_phy_anfc_merged-uv_PT1H-i.nc"
    ds = _nc(p2)
    dims3 = ("time", "latitude", "longitude")
    shape3 = (HOURS.size, LAT.size, LON.size)
    for name, val, std in (("uo", 0.5, "eastward_sea_water_velocity"),
                           ("vo", 0.0, "northward_sea_water_velocity"),
                           ("utotal", 0.7, "surface_eastward_sea_water_velocity"),
                           ("vtotal", -0.2, "surface_northward_sea_water_velocity")):
        _float(ds, name, dims3, _field(shape3, val), {"units": "m s-1", "standard_name": std})
    ds.close()
    got = open_file(p2)
    assert got[cv.CURRENT_U].attrs["source_variable"] == "utotal"
    assert float(got[cv.CURRENT_V][0, 0, 0]) == pytest.approx(-0.2)


def test_wavewatch3_ounf_names_and_peak_frequency(tmp_path: Path) -> None:
    p = tmp_path / "ww3.202603.nc"
    ds = _nc(p, time_units="days since 1990-01-01 00:00:00")
    ds["time"][:] = (np.datetime64("2026-03-03", "D") - np.datetime64("1990-01-01", "D")
                     ).astype(np.int64) + HOURS / 24.0
    shape = (HOURS.size, LAT.size, LON.size)
    dims = ("time", "latitude", "longitude")
    _packed(ds, "hs", dims, _field(shape, 4.0), {
        "units": "m", "standard_name": "sea_surface_wave_significant_height",
        "globwave_name": "significant_wave_height"}, scale=0.002)
    _packed(ds, "dir", dims, _field(shape, 200.0), {
        "units": "degree", "standard_name": "sea_surface_wave_from_direction",
        "globwave_name": "wave_from_direction"}, scale=0.1)
    _packed(ds, "fp", dims, _field(shape, 0.08), {
        "units": "s-1", "standard_name": "sea_surface_wave_peak_frequency"}, scale=1e-4)
    _packed(ds, "uwnd", dims, _field(shape, 7.0), {"units": "m s-1",
                                                   "standard_name": "eastward_wind"}, scale=0.1)
    _packed(ds, "vwnd", dims, _field(shape, 0.0), {"units": "m s-1",
                                                   "standard_name": "northward_wind"}, scale=0.1)
    _packed(ds, "ucur", dims, _field(shape, 0.0), {
        "units": "m s-1", "standard_name": "eastward_sea_water_velocity"})
    _packed(ds, "vcur", dims, _field(shape, -0.5), {
        "units": "m s-1", "standard_name": "northward_sea_water_velocity"})
    ds.close()
    got = open_file(p)
    assert float(got[cv.WAVE_HS][0, 0, 0]) == pytest.approx(4.0, abs=0.002)
    # fp = 0.08 Hz -> Tp = 12.5 s -> Tm01 = 0.837 Tp
    assert float(got[cv.WAVE_TM][0, 0, 0]) == pytest.approx(12.5 * to_tm01_factor("tp"),
                                                            rel=1e-3)
    assert float(got[cv.CURRENT_V][0, 0, 0]) == pytest.approx(-0.5, abs=0.01)
    assert float(got[cv.WIND_U][0, 0, 0]) == pytest.approx(7.0, abs=0.05)
    # WW3 t02 when no fp: Tm02 converted to Tm01
    p2 = tmp_path / "ww3_t02.nc"
    ds = _nc(p2)
    _float(ds, "hs", dims, _field(shape, 4.0), {"units": "m"})
    _float(ds, "t02", dims, _field(shape, 6.0), {"units": "s"})
    ds.close()
    got = open_file(p2)
    assert float(got[cv.WAVE_TM][0, 0, 0]) == pytest.approx(6.0 * to_tm01_factor("tm02"),
                                                            rel=1e-5)


def test_ensemble_members_are_all_kept_along_member(tmp_path: Path) -> None:
    p = tmp_path / "ens.nc"
    members = np.arange(5.0)
    ds = _nc(p, extra_dims={"realization": (members, {"standard_name": "realization"})})
    shape = (HOURS.size, members.size, LAT.size, LON.size)
    dims = ("time", "realization", "latitude", "longitude")
    u = np.broadcast_to((members * 2.0)[None, :, None, None], shape)  # 0, 2, 4, 6, 8 m/s
    _float(ds, "u10", dims, u, {"units": "m s-1"})
    _float(ds, "v10", dims, np.zeros(shape), {"units": "m s-1"})
    _float(ds, "swh", dims, np.ones(shape), {"units": "m"})
    ds.close()
    got = open_forecast([p])
    assert got.sizes["member"] == 5 and got[cv.WIND_U].dims[0] == "member"
    assert np.allclose(got[cv.WIND_U].values[:, 0, 0, 0], members * 2.0)
    # labelled by the file's realization numbers; nothing averaged or dropped, and said
    assert list(got["member_label"].values) == ["0", "1", "2", "3", "4"]
    assert "5 members kept from dimension 'realization'" in got.attrs["ensemble"]
    assert any("ensemble" in n for n in load_notes(got))
