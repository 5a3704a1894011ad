"""SeaState construction, STAWAVE-2 and wind terms, seakeeping and IMO checks."""


import numpy as np
import pytest
from shiproute_core.units import M_S_PER_KNOT
from shiproute_planner.ship import PhysicsModel, SeaState, load_ship
from shiproute_planner.ship.seakeeping import (
    imo_flags,
    natural_roll_period_s,
    relative_motion_rao2,
)
from shiproute_planner.ship.spectra import D_OMEGA, ittc_unit, jonswap_unit
from shiproute_planner.ship.waves import direction_factor
from shiproute_planner.ship.wind import blendermann_caa, relative_wind


@pytest.fixture(scope="module")
def model() -> PhysicsModel:
    return PhysicsModel(load_ship("container_4600teu"))


def test_from_forecast_nan_is_calm_and_total_sea_is_split():
    sample = {
        "eastward_wind": np.array([np.nan, 10.0]),
        "northward_wind": np.array([0.0, 0.0]),
        "sea_surface_wave_significant_height": np.array([np.nan, 5.0]),
        "sea_surface_wave_from_direction": np.array([0.0, 200.0]),
        "sea_surface_wave_mean_period": np.array([np.nan, 9.0]),
    }
    s = SeaState.from_forecast(sample)
    assert s.wind_u_m_s[0] == 0 and s.hs_m[0] == 0
    assert s.hs_m[1] == pytest.approx(5.0)
    assert s.wind_wave_hs_m[1] == pytest.approx(0.21 * 100 / 9.80665)  # fully developed part
    assert s.wind_wave_from_deg[1] == pytest.approx(270.0)  # wind blowing east comes from west
    assert s.swell_from_deg[1] == 200.0


def test_spectra_normalised():
    for spec in (ittc_unit(np.array([5.0, 9.0])), jonswap_unit(np.array([8.0, 12.0]))):
        assert np.sum(spec, axis=-1) * D_OMEGA == pytest.approx(1 / 16, rel=0.03)


def test_stawave_scales_with_hs_squared_and_validity(model):
    v, h = np.array([8.0]), np.array([0.0])
    def r_wave(hs, from_deg):
        sea = SeaState.from_arrays(wind_wave_hs_m=hs, wind_wave_from_deg=from_deg,
                                   wind_wave_period_s=7.0)
        return model.added_resistance_n(v, h, sea)[1][0]
    assert r_wave(4.0, 0.0) == pytest.approx(4 * r_wave(2.0, 0.0), rel=1e-9)
    assert r_wave(2.0, 30.0) == r_wave(2.0, 0.0)  # inside +-45 deg
    assert 0 < r_wave(2.0, 60.0) < r_wave(2.0, 0.0)
    assert r_wave(2.0, 100.0) == 0.0
    assert list(direction_factor(np.array([0, 45, 67.5, 90, 180]))) == pytest.approx(
        [1, 1, 0.5, 0, 0])


def test_wind_conventions_and_coefficients():
    spd, ang = relative_wind(np.array([5.0]), np.array([0.0]), np.array([0.0]), np.array([-10.0]))
    assert spd[0] == pytest.approx(15.0) and ang[0] == pytest.approx(0.0)  # head wind
    spd, ang = relative_wind(np.array([5.0]), np.array([90.0]), np.array([0.0]), np.array([0.0]))
    assert ang[0] == pytest.approx(0.0)  # still air is a head wind of the ship's speed
    caa = blendermann_caa("blendermann_container_loaded", 1000.0, 4500.0)
    assert caa[0] == pytest.approx(0.55) and caa[-1] == pytest.approx(-0.55)
    assert abs(caa[9]) < 1e-12  # beam wind adds no longitudinal force


def test_relative_motion_limits(model):
    ship = model.ship
    L = ship.hull.lpp_m
    rao2 = relative_motion_rao2(ship, np.array([0.0]), np.array([0.0]), 0.5 * L)[0]
    from shiproute_planner.ship.spectra import OMEGA_RAD_S
    long_wave = OMEGA_RAD_S < 0.2
    short_wave = OMEGA_RAD_S > 2.0
    assert np.all(rao2[long_wave] < 0.1)  # ship follows long waves
    assert np.all(np.abs(rao2[short_wave] - 1.0) < 0.1)  # short waves pass unfollowed


def test_seakeeping_probabilities_grow_with_hs_and_imo_checks(model):
    p = []
    for hs in (2.0, 5.0, 8.0):
        sea = SeaState.from_arrays(wind_wave_hs_m=hs, wind_wave_from_deg=0.0,
                                   wind_wave_period_s=3.5 + hs)
        r = model.evaluate(77.0, 0.0, sea)
        p.append((float(r.p_slamming), float(r.p_deck_wetness), float(r.p_propeller_emergence)))
    p = np.array(p)
    assert np.all(np.diff(p, axis=0) >= 0) and p[-1, 2] > p[0, 2]
    tr = natural_roll_period_s(model.ship)
    assert 15 < tr < 30  # IS Code estimate for B 37.5 m, GM 1.5 m
    ship = model.ship
    one = np.array([1.0])
    hs = np.array([4.0])
    # surf-riding: V > 1.8 sqrt(L) / cos(180 - alpha) kn in following/quartering seas
    fast = one * 1.9 * np.sqrt(ship.hull.lpp_m) * M_S_PER_KNOT
    surf, *_ = imo_flags(ship, fast, hs, one * 10.0, one * 180.0, "jonswap")
    assert surf[0]
    surf, *_ = imo_flags(ship, fast, hs, one * 10.0, one * 140.0, "jonswap")
    assert not surf[0]  # cos(40 deg) lowers the effective speed below the threshold
    surf, *_ = imo_flags(ship, fast, hs, one * 10.0, one * 0.0, "jonswap")
    assert not surf[0]
    # resonances at zero speed: encounter period = wave peak period
    t01_sync = tr * 0.834
    _, param, sync, _ = imo_flags(ship, 0 * one, hs, one * t01_sync, one * 0.0, "jonswap")
    assert sync[0] and not param[0]
    _, param, sync, _ = imo_flags(ship, 0 * one, hs, one * t01_sync / 2, one * 0.0, "jonswap")
    assert param[0] and not sync[0]
    # successive high waves: wave length > 0.8 L and Hs > 0.04 L
    *_, high = imo_flags(ship, 0 * one, one * 10.0, one * 12.0, one * 0.0, "jonswap")
    assert high[0]
    *_, high = imo_flags(ship, 0 * one, one * 2.5, one * 12.0, one * 0.0, "jonswap")
    assert not high[0]


def test_from_forecast_partial_partition_uses_total_remainder():
    sample = {
        "sea_surface_wave_significant_height": np.array([5.0, 5.0, 3.0]),
        "sea_surface_wave_from_direction": np.array([10.0, 10.0, 10.0]),
        "sea_surface_wave_mean_period": np.array([9.0, 9.0, 9.0]),
        "sea_surface_swell_wave_significant_height": np.array([3.0, np.nan, 1.0]),
        "sea_surface_swell_wave_from_direction": np.array([250.0, np.nan, 250.0]),
        "sea_surface_swell_wave_mean_period": np.array([13.0, np.nan, 12.0]),
        "sea_surface_wind_wave_significant_height": np.array([np.nan, np.nan, 2.5]),
    }
    s = SeaState.from_forecast(sample)
    assert s.wind_wave_hs_m[0] == pytest.approx(4.0)  # sqrt(5^2 - 3^2)
    assert s.swell_hs_m[0] == 3.0 and s.swell_period_s[0] == 13.0
    assert s.hs_m[1] == pytest.approx(5.0)  # nothing partitioned: split of the total
    assert s.wind_wave_hs_m[2] == 2.5 and s.swell_hs_m[2] == 1.0
