"""Plans state what they were made with: estimated waves, coverage in time, several sources in
one cycle; the physics answers point the right way (head-sea waves cost fuel, a following
Gulf Stream saves it)."""

from __future__ import annotations

from datetime import timedelta
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from shiproute_planner.errors import InvalidVoyageError
from shiproute_planner.plan_setup import load_forecast
from shiproute_planner.planning import plan_voyage
from shiproute_weather.contract import canonical as cv
from shiproute_weather.sampling.sampler import ForecastSampler

CMEMS_NATL = Path("/work/shared/data/forecasts/cmems_glo12_currents_2024-01-01_natl.nc")
TIGGE_2007 = Path("/usr/share/doc/python-grib-doc/examples/ecmwf_tigge.grb")
_WAVES = (cv.WAVE_HS, cv.WIND_WAVE_HS)


def _gfs_like_wind(path: Path, u_m_s: float, v_m_s: float, start: str, hours: int,
                   lat: tuple[float, float], lon: tuple[float, float]) -> Path:
    """A GFS-like wind-only NetCDF (NOMADS names, 0..360 longitudes, north -> south rows)."""
    la = np.arange(lat[1], lat[0] - 1e-9, -0.5)
    lo = np.arange(lon[0] % 360.0, lon[1] % 360.0 + 1e-9, 0.5)
    t = np.datetime64(start, "ns") + np.arange(0, hours + 1, 3) * np.timedelta64(1, "h")
    shape = (t.size, la.size, lo.size)
    ds = xr.Dataset({"ugrd10m": (("time", "lat", "lon"), np.full(shape, u_m_s, np.float32),
                                 {"units": "m/s", "long_name": "10 m u wind"}),
                     "vgrd10m": (("time", "lat", "lon"), np.full(shape, v_m_s, np.float32),
                                 {"units": "m/s"})},
                    coords={"time": t, "lat": la, "lon": lo}, attrs={"source": "test GFS"})
    ds.to_netcdf(path)
    return path


def _plan(a: str, b: str, depart: str, hours: float, forecast, **kw):
    sampler = forecast if forecast is None else ForecastSampler(forecast)
    return plan_voyage(a, b, depart, timedelta(hours=hours), "container_4600teu", sampler,
                       method="great_circle", coastal_passage=False, with_baseline=False,
                       budget_s=30.0, **kw)


def test_wind_only_gale_plans_with_estimated_waves(tmp_path: Path, land_mask) -> None:
    # a near gale (18 m/s, Beaufort 8) from the east over open Atlantic; the ship heads east
    path = _gfs_like_wind(tmp_path / "gfs_wind.nc", -18.0, 0.0, "2026-03-03T00", 48,
                          (35.0, 45.0), (-55.0, -35.0))
    fc = load_forecast([str(path)])
    assert all(n in fc for n in _WAVES)
    hs = float(fc[cv.WAVE_HS].values[-1, 10, 20])
    # fetch/duration-limited growth stays below the fully developed Pierson-Moskowitz sea
    # (0.241 U^2 / g = 8.0 m) and above a one-day-old sea's lower bound
    assert 3.0 < hs <= 0.241 * 18.0**2 / 9.81 + 1e-3
    zeroed = fc.copy()
    for n in _WAVES:
        zeroed[n] = fc[n] * 0.0
    with_waves = _plan("40.0,-50.0", "40.0,-40.0", "2026-03-03T12:00Z", 36.0, fc, land=land_mask)
    calm_sea = _plan("40.0,-50.0", "40.0,-40.0", "2026-03-03T12:00Z", 36.0, zeroed,
                     land=land_mask)
    assert with_waves.total_fuel_t > calm_sea.total_fuel_t * 1.02  # head seas cost fuel
    assert any(w.startswith("waves estimated from wind") for w in with_waves.warnings)
    assert any("no currents" in w for w in with_waves.warnings)
    block = with_waves.extra["forecast"]
    assert block["fields"][cv.WAVE_HS]["source_file"] == str(path)
    assert block["covered_pct"] == pytest.approx(100.0)
    with pytest.raises(InvalidVoyageError, match=r"gfs_wind\.nc.*wind only"):
        load_forecast([str(path)], waves_from_wind=False)


def test_voyage_twice_the_forecast_length_states_its_coverage(tmp_path: Path,
                                                              land_mask) -> None:
    path = _gfs_like_wind(tmp_path / "short.nc", 3.0, 0.0, "2026-03-03T00", 36,
                          (30.0, 50.0), (-60.0, -20.0))
    plan = _plan("40.0,-55.0", "40.0,-30.0", "2026-03-03T00:00Z", 72.0,
                 load_forecast([str(path)]), land=land_mask, persistence_h=24.0)
    block = plan.extra["forecast"]
    voyage_h = (plan.eta_s - plan.departure_s) / 3600.0
    assert block["covered_hours"] == pytest.approx(36.0, abs=1e-6)
    assert block["persistence_hours"] == pytest.approx(24.0, abs=1e-6)
    assert block["calm_hours"] == pytest.approx(voyage_h - 60.0, abs=1e-6)
    assert block["covered_pct"] == pytest.approx(100.0 * 36.0 / voyage_h)
    text = " ".join(plan.warnings)
    assert f"covers 36.0 h of the {voyage_h:.1f} h voyage" in text
    assert "persistence" in text and "calm water assumed" in text


@pytest.mark.skipif(not TIGGE_2007.exists(), reason="python-grib-doc not installed")
def test_a_forecast_from_another_year_is_refused(tmp_path: Path, capsys) -> None:
    from shiproute_planner.cli.plan import main

    code = main(["--from", "40.0,-50.0", "--to", "40.0,-40.0", "--depart", "2026-03-03T00:00Z",
                 "--rta", "36h", "--forecast", str(TIGGE_2007), "--out", str(tmp_path),
                 "--method", "great_circle", "--no-plot"])
    err = capsys.readouterr().err
    assert code == 2
    assert "2007-05-10" in err and "does not overlap" in err and "Traceback" not in err


@pytest.mark.skipif(not CMEMS_NATL.exists(), reason="shared CMEMS currents not available")
def test_two_file_cycle_following_gulf_stream_saves_fuel(tmp_path: Path, land_mask) -> None:
    # light westerly wind from one file, real CMEMS GLO12 currents of 2024-01-01 from another
    wind = _gfs_like_wind(tmp_path / "wind.nc", 3.0, 0.0, "2024-01-01T00", 36,
                          (30.0, 45.0), (-80.0, -60.0))
    fc = load_forecast([str(wind), str(CMEMS_NATL)])
    assert fc[cv.CURRENT_U].attrs["source_file"] == str(CMEMS_NATL)
    assert fc[cv.WIND_U].attrs["source_file"] == str(wind)
    no_current = fc.drop_vars([cv.CURRENT_U, cv.CURRENT_V])
    # Cape Hatteras -> south of the Grand Banks along the Gulf Stream's core (~1.5 m/s NE)
    a, b = "35.6,-74.3", "38.0,-68.0"
    down = _plan(a, b, "2024-01-01T00:00Z", 24.0, fc, land=land_mask)
    down_still = _plan(a, b, "2024-01-01T00:00Z", 24.0, no_current, land=land_mask)
    up = _plan(b, a, "2024-01-01T00:00Z", 24.0, fc, land=land_mask)
    up_still = _plan(b, a, "2024-01-01T00:00Z", 24.0, no_current, land=land_mask)
    assert down.total_fuel_t < 0.95 * down_still.total_fuel_t  # a following current helps
    assert up.total_fuel_t > 1.05 * up_still.total_fuel_t  # a head current costs
    block = down.extra["forecast"]
    assert set(block["source_files"]) == {str(wind), str(CMEMS_NATL)}
    assert block["fields"][cv.CURRENT_V]["source_file"] == str(CMEMS_NATL)
    assert any("held (persistence" in w for w in down.warnings)  # a one-time daily mean
    assert any("no currents" in w for w in down_still.warnings)


def test_node_path_states_the_cycle_announcement() -> None:
    """The planner node plans on a sampler packed from slices: the announcement's field
    sources and load notes become its record, and the plan's statement repeats them."""
    pytest.importorskip("shiproute_msgs.msg")
    from types import SimpleNamespace

    from shiproute_planner.forecast_statement import forecast_statement
    from shiproute_planner.ros.convert import cycle_record
    from shiproute_weather.contract.canonical import Grid

    from shiproute_msgs.msg import ForecastCycle

    msg = ForecastCycle(cycle_id="c1", fields=[cv.WIND_U, cv.WIND_V, cv.WAVE_HS],
                        source_files=["gfs.grib2"],
                        field_sources=["gfs.grib2", "gfs.grib2", "gfs.grib2"],
                        notes=["waves estimated from wind (...)",
                               "no currents in the forecast: currents taken as zero"])
    grid = Grid(30.0, 1.0, 11, -60.0, 1.0, 21)  # 30-40 N, 60-40 W
    times = np.array([0.0, 6 * 3600.0])
    sampler = ForecastSampler.from_packed(np.zeros((2, 11, 21, 3), np.float32), times, grid,
                                          [cv.WIND_U, cv.WIND_V, cv.WAVE_HS])
    sampler.record = cycle_record(msg)
    wp = [SimpleNamespace(lat_deg=35.0, lon_deg=-55.0 + 10.0 * k, leg_duration_s=6 * 3600.0,
                          leg_distance_nm=100.0) for k in range(3)]  # the last one off grid
    plan = SimpleNamespace(departure_s=0.0, eta_s=12 * 3600.0, waypoints=wp, cycle_id="c1")
    block, warnings = forecast_statement(sampler, plan, persistence_h=24.0)
    assert block["fields"][cv.WAVE_HS]["source_file"] == "gfs.grib2"
    assert "waves estimated from wind (...)" in warnings
    assert any("no currents" in w for w in warnings)
    assert block["covered_hours"] == pytest.approx(6.0)
    assert block["persistence_hours"] == pytest.approx(6.0)
    assert block["outside_grid_hours"] == pytest.approx(6.0)  # the leg reaching 35 W
    assert any("outside the forecast grid" in w for w in warnings)
