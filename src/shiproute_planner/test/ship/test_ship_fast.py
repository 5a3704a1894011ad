"""The tabulated fast model agrees with the direct physics solve (< 0.5 %) and is cached.

Marked slow: the first use compiles the numba kernel (cached on disk afterwards).
"""

import numpy as np
import pytest
from shiproute_planner.ship import (
    FastModel,
    InputRangeError,
    PerformanceModel,
    SeaState,
    fast_model,
    load_ship,
)

pytestmark = pytest.mark.slow


def _random_legs(rng, n):
    sea = SeaState.from_arrays(
        wind_u_m_s=rng.uniform(-20, 20, n), wind_v_m_s=rng.uniform(-20, 20, n),
        wind_wave_hs_m=rng.uniform(0, 7, n), wind_wave_from_deg=rng.uniform(0, 360, n),
        wind_wave_period_s=rng.uniform(2.5, 11, n), swell_hs_m=rng.uniform(0, 5, n),
        swell_from_deg=rng.uniform(0, 360, n), swell_period_s=rng.uniform(6, 18, n),
        current_u_m_s=rng.uniform(-1.5, 1.5, n), current_v_m_s=rng.uniform(-1.5, 1.5, n),
    )
    return rng.uniform(25, 110, n), rng.uniform(0, 360, n), sea


@pytest.mark.parametrize("name", ["container_4600teu", "vlcc_270k", "bulk_supramax"])
def test_fast_matches_physics_within_half_percent(name):
    fm = fast_model(load_ship(name))
    rpm, hdg, sea = _random_legs(np.random.default_rng(3), 1500)
    rpm = rpm * fm.ship.engine.rpm_max / 104.0
    a, b = fm.evaluate(rpm, hdg, sea), fm.physics.evaluate(rpm, hdg, sea)
    moving = b.stw_m_s > 0.5
    for k in ("stw_m_s", "brake_power_kw", "fuel_t_per_h", "engine_load"):
        x, y = getattr(a, k)[moving], getattr(b, k)[moving]
        assert np.max(np.abs(x / y - 1)) < 0.005, k
    # SOG adds the (identical) current vector: its error is the STW error, so compare to STW
    d_sog = np.abs(a.sog_m_s - b.sog_m_s)[moving]
    assert np.max(d_sog / b.stw_m_s[moving]) < 0.005
    for k in ("p_slamming", "p_deck_wetness", "p_propeller_emergence"):
        assert np.max(np.abs(getattr(a, k) - getattr(b, k))) < 0.02, k
    for k in ("engine_limit_exceeded", "surf_riding", "parametric_roll", "synchronous_roll",
              "high_wave_group"):
        assert np.mean(getattr(a, k) != getattr(b, k)) < 0.01, k


def test_cached_per_ship_and_condition_and_inverse():
    a = fast_model(load_ship("container_4600teu"))
    assert fast_model(load_ship("container_4600teu")) is a
    assert fast_model(load_ship("container_4600teu", "ballast")) is not a
    assert isinstance(a, FastModel) and isinstance(a, PerformanceModel)
    rpm, hdg, sea = _random_legs(np.random.default_rng(9), 200)
    rpm = np.clip(rpm, 40, 100)
    r = a.evaluate(rpm, hdg, sea)
    ok = r.stw_m_s > 2.0
    sub = SeaState(**{k: v[ok] for k, v in vars(sea).items()})
    back = a.rpm_for_speed(r.stw_m_s[ok], hdg[ok], sub)
    assert np.max(np.abs(back / rpm[ok] - 1)) < 0.005


def test_shapes_threads_and_errors():
    fm = fast_model(load_ship("container_4600teu"))
    rpm, hdg, sea = _random_legs(np.random.default_rng(5), 30000)  # split over threads
    small = fm.evaluate(np.full((4, 3), 77.0), np.zeros(3), SeaState.calm())
    assert small.fuel_t_per_h.shape == (4, 3)
    r2 = fm.evaluate(rpm, hdg, sea)
    ref = fm.evaluate(rpm[:100], hdg[:100], SeaState(**{k: v[:100] for k, v in vars(sea).items()}))
    assert np.array_equal(r2.stw_m_s[:100], ref.stw_m_s)
    with pytest.raises(InputRangeError):
        fm.evaluate(np.array([77.0, np.inf]), 0.0, SeaState.calm())


def test_split_evaluation_works_in_a_forked_child():
    import multiprocessing as mp

    fm = fast_model(load_ship("container_4600teu"))
    rpm = np.full(30000, 77.0)  # large enough to use the thread pool
    expected = float(fm.evaluate(rpm, 0.0, SeaState.calm()).stw_m_s.mean())
    ctx = mp.get_context("fork")
    queue = ctx.Queue()

    def child() -> None:
        queue.put(float(fm.evaluate(rpm, 0.0, SeaState.calm()).stw_m_s.mean()))

    proc = ctx.Process(target=child)
    proc.start()
    try:
        assert queue.get(timeout=120) == pytest.approx(expected)
    finally:
        proc.join(timeout=30)
