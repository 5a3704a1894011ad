"""Performance profile NetCDF: export -> import reproduces the physics model on grid points."""


import numpy as np
import pytest
import xarray as xr
from shiproute_core.units import M_S_PER_KNOT
from shiproute_planner.ship import PhysicsModel, ProfileError, SeaState, load_ship
from shiproute_planner.ship.profile import (
    ProfileGrid,
    ProfileModel,
    export_profile,
    grid_sea,
)

GRID = ProfileGrid(
    rpm=(40.0, 60.0, 80.0, 100.0), hs_m=(0.0, 2.5, 5.0), rel_wave_deg=(0.0, 60.0, 120.0, 180.0),
    wind_speed_m_s=(0.0, 10.0, 20.0), rel_wind_deg=(0.0, 90.0, 180.0),
)


@pytest.fixture(scope="module")
def setup(tmp_path_factory):
    ship = load_ship("container_4600teu")
    physics = PhysicsModel(ship)
    path = tmp_path_factory.mktemp("profile") / "p.nc"
    export_profile(physics, path, GRID)
    return ship, physics, path


def test_round_trip_on_grid_points(setup):
    ship, physics, path = setup
    model = ProfileModel(ship, path)
    rpm, hdg, sea = grid_sea(GRID)
    rot = 37.0  # same relative geometry with the ship heading 37 deg
    sea_rot = SeaState(**{
        **vars(sea),
        "wind_u_m_s": sea.wind_u_m_s * np.cos(np.radians(rot)) + sea.wind_v_m_s * np.sin(
            np.radians(rot)),
        "wind_v_m_s": -sea.wind_u_m_s * np.sin(np.radians(rot)) + sea.wind_v_m_s * np.cos(
            np.radians(rot)),
        "wind_wave_from_deg": sea.wind_wave_from_deg + rot,
    })
    a, b = model.evaluate(rpm, hdg + rot, sea_rot), physics.evaluate(rpm, hdg, sea)
    for k in ("stw_m_s", "brake_power_kw", "fuel_t_per_h"):
        assert np.max(np.abs(getattr(a, k) / getattr(b, k) - 1)) < 0.01, k


def test_between_grid_points_stays_close(setup):
    ship, physics, path = setup
    model = ProfileModel(ship, path)
    sea = SeaState.from_arrays(wind_v_m_s=-12.0, wind_wave_hs_m=3.5, wind_wave_from_deg=0.0,
                               wind_wave_period_s=3.86 * np.sqrt(3.5))
    a, b = model.evaluate(77.0, 0.0, sea), physics.evaluate(77.0, 0.0, sea)
    assert float(a.stw_m_s) == pytest.approx(float(b.stw_m_s), rel=0.03)
    assert model.rpm_for_speed(a.stw_m_s, 0.0, sea) == pytest.approx(77.0, rel=0.01)


def test_speed_axis_profile_and_errors(setup, tmp_path):
    ship, physics, path = setup
    ds = xr.load_dataset(path)
    speeds = np.array([8.0, 12.0, 16.0, 20.0])
    calm = SeaState.calm()
    rpm_speed = physics.rpm_for_speed(speeds * M_S_PER_KNOT, 0.0, calm)
    by_speed = xr.Dataset(
        {
            "rpm": (("stw_kn",), rpm_speed),
            "brake_power_kw": (("stw_kn",), physics.evaluate(rpm_speed, 0.0, calm).brake_power_kw),
            "fuel_t_per_h": (("stw_kn",), physics.evaluate(rpm_speed, 0.0, calm).fuel_t_per_h),
        },
        coords={"stw_kn": speeds},
    ).expand_dims({d: ds[d].values for d in ("hs_m", "rel_wave_deg", "wind_speed_m_s",
                                              "rel_wind_deg")}, axis=[1, 2, 3, 4])
    p2 = tmp_path / "speed.nc"
    by_speed.to_netcdf(p2)
    m2 = ProfileModel(ship, p2)
    r = m2.evaluate(rpm_speed[1], 0.0, calm)
    assert float(r.stw_m_s) == pytest.approx(12.0 * M_S_PER_KNOT, rel=1e-6)
    bad = tmp_path / "bad.nc"
    ds.drop_vars("fuel_t_per_h").to_netcdf(bad)
    with pytest.raises(ProfileError, match="fuel_t_per_h"):
        ProfileModel(ship, bad)
