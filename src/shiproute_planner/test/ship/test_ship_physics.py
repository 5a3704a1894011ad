"""Physics model sanity: monotonicity, weather effects, currents, calm limit, ranges."""


import numpy as np
import pytest
from shiproute_core.units import M_S_PER_KNOT
from shiproute_planner.ship import InputRangeError, PhysicsModel, SeaState, load_ship


@pytest.fixture(scope="module")
def model() -> PhysicsModel:
    return PhysicsModel(load_ship("container_4600teu"))


def _head_sea(hs: float, heading: float = 0.0) -> SeaState:
    return SeaState.from_arrays(
        wind_v_m_s=-2.5 * hs, wind_wave_hs_m=hs, wind_wave_from_deg=heading,
        wind_wave_period_s=3.0 + hs, swell_hs_m=hs / 2, swell_from_deg=heading,
        swell_period_s=11.0,
    )


def test_more_rpm_gives_more_speed_and_fuel(model):
    rpm = np.linspace(30, 104, 15)
    for sea in (SeaState.calm(), _head_sea(4.0)):
        r = model.evaluate(rpm, 0.0, sea)
        assert np.all(np.diff(r.stw_m_s) > 0)
        assert np.all(np.diff(r.fuel_t_per_h) > 0)
        assert np.all(np.diff(r.brake_power_kw) > 0)


def test_head_seas_reduce_speed_and_raise_fuel_more_than_following(model):
    calm = model.evaluate(77.0, 0.0, SeaState.calm())
    head = model.evaluate(77.0, 0.0, _head_sea(5.0))
    follow = model.evaluate(77.0, 180.0, _head_sea(5.0))
    assert head.stw_m_s < 0.95 * calm.stw_m_s
    assert head.stw_m_s < follow.stw_m_s
    assert head.fuel_t_per_h > calm.fuel_t_per_h
    speeds = [model.evaluate(77.0, 0.0, _head_sea(h)).stw_m_s for h in (1, 3, 5, 7)]
    assert np.all(np.diff(np.ravel(speeds)) < 0)


def test_waves_beyond_beam_add_no_resistance(model):
    sea = SeaState.from_arrays(wind_wave_hs_m=4.0, wind_wave_from_deg=180.0)  # from astern
    assert model.evaluate(77.0, 0.0, sea).stw_m_s == pytest.approx(
        model.evaluate(77.0, 0.0, SeaState.calm()).stw_m_s, rel=1e-9
    )


def test_following_current_raises_sog_and_cross_current_turns_cog(model):
    calm = model.evaluate(77.0, 90.0, SeaState.calm())
    with_current = model.evaluate(77.0, 90.0, SeaState.from_arrays(current_u_m_s=1.0))
    assert with_current.sog_m_s == pytest.approx(calm.sog_m_s + 1.0, rel=1e-9)
    assert with_current.stw_m_s == pytest.approx(calm.stw_m_s, rel=1e-12)
    cross = model.evaluate(77.0, 90.0, SeaState.from_arrays(current_v_m_s=1.0))
    assert 80.0 < float(cross.cog_deg) < 90.0


def test_zero_weather_equals_calm(model):
    rpm = np.array([40.0, 77.0, 100.0])
    a = model.evaluate(rpm, 123.0, SeaState.calm(3))
    b = model.evaluate(rpm, 123.0, SeaState.from_arrays(wind_wave_period_s=6.0))
    for k, v in a.as_dict().items():
        assert np.array_equal(v, getattr(b, k)), k
    assert np.all(a.p_slamming == 0) and not a.surf_riding.any()


def test_finite_everywhere_in_range_and_shapes_broadcast(model):
    rng = np.random.default_rng(7)
    shape = (40, 25)
    sea = SeaState.from_arrays(
        wind_u_m_s=rng.uniform(-30, 30, shape), wind_v_m_s=rng.uniform(-30, 30, shape),
        wind_wave_hs_m=rng.uniform(0, 14, shape), wind_wave_from_deg=rng.uniform(0, 360, shape),
        wind_wave_period_s=rng.uniform(1, 20, shape), swell_hs_m=rng.uniform(0, 10, shape),
        swell_from_deg=rng.uniform(-360, 360, shape), swell_period_s=rng.uniform(4, 25, shape),
        current_u_m_s=rng.uniform(-2, 2, shape), current_v_m_s=rng.uniform(-2, 2, shape),
    )
    r = model.evaluate(rng.uniform(1, 150, shape[1]), rng.uniform(-360, 720, shape), sea)
    for k, v in r.as_dict().items():
        assert v.shape == shape, k
        assert np.all(np.isfinite(v)), k
    assert np.all(r.stw_m_s >= 0)
    for k in ("p_slamming", "p_deck_wetness", "p_propeller_emergence"):
        assert np.all((getattr(r, k) >= 0) & (getattr(r, k) <= 1))


def test_engine_limits_reported_not_clipped(model):
    r = model.evaluate(np.array([20.0, 77.0, 110.0]), 0.0, SeaState.calm())
    assert list(r.engine_limit_exceeded) == [True, False, True]
    assert r.stw_m_s[2] > r.stw_m_s[1]  # still solved physically
    heavy = model.evaluate(104.0, 0.0, _head_sea(7.0))
    assert bool(heavy.engine_limit_exceeded)  # torque limit in heavy weather at full RPM


def test_clear_errors_outside_range(model):
    with pytest.raises(InputRangeError, match="input 'rpm'"):
        model.evaluate(-5.0, 0.0, SeaState.calm())
    with pytest.raises(InputRangeError, match="wind_wave_hs_m"):
        model.evaluate(77.0, 0.0, SeaState.from_arrays(wind_wave_hs_m=40.0))
    with pytest.raises(InputRangeError, match="NaN"):
        model.evaluate(np.nan, 0.0, SeaState.calm())


def test_rpm_for_speed_inverts_evaluate(model):
    sea = _head_sea(3.0, heading=20.0)
    rpm = np.array([45.0, 70.0, 95.0])
    r = model.evaluate(rpm, 0.0, sea)
    assert model.rpm_for_speed(r.stw_m_s, 0.0, sea) == pytest.approx(rpm, rel=1e-4)


def test_all_bundled_ships_make_plausible_service_speed():
    for name, (lo, hi) in {
        "container_4600teu": (21, 25), "vlcc_270k": (14, 17), "bulk_supramax": (13, 15.5),
        "container_348m": (22, 26),
    }.items():
        ship = load_ship(name)
        r = PhysicsModel(ship).evaluate(ship.engine.rpm_mcr, 0.0, SeaState.calm())
        assert lo < float(r.stw_m_s) / M_S_PER_KNOT < hi, name
        assert 0.8 < float(r.engine_load) < 1.0, name  # sea margin at rated speed
