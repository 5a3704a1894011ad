"""Kwon's speed-loss model: published coefficient forms and behaviour behind the interface."""

import numpy as np
import pytest
from shiproute_planner.ship import PerformanceModel, SeaState, load_ship
from shiproute_planner.ship.kwon import (
    KwonModel,
    beaufort_number,
    direction_coefficient,
    form_coefficient,
    speed_coefficient,
)


@pytest.fixture(scope="module")
def kwon() -> KwonModel:
    return KwonModel(load_ship("container_348m"))


def test_coefficients():
    bn = np.array([6.0])
    assert direction_coefficient(bn, np.array([10.0]))[0] == 1.0  # head sea
    assert direction_coefficient(bn, np.array([90.0]))[0] == pytest.approx(0.45)  # (0.9)/2
    assert direction_coefficient(np.array([8.0]), np.array([170.0]))[0] == pytest.approx(0.2)
    assert speed_coefficient(0.70, np.array([0.2]), False)[0] == pytest.approx(
        3.1 - 5.3 * 0.2 - 12.4 * 0.04)
    assert form_coefficient(np.array([0.0]), 1e5, "container", False)[0] == 0.0
    assert beaufort_number(np.array([0.0, 0.836]))[1] == pytest.approx(1.0)


def test_kwon_model_behaviour(kwon):
    assert isinstance(kwon, PerformanceModel)
    calm = kwon.evaluate(80.0, 0.0, SeaState.calm())
    storm = SeaState.from_arrays(wind_v_m_s=-20.0, wind_wave_hs_m=5.0)
    head = kwon.evaluate(80.0, 0.0, storm)
    follow = kwon.evaluate(80.0, 180.0, storm)
    assert head.stw_m_s < follow.stw_m_s < calm.stw_m_s
    assert head.fuel_t_per_h == pytest.approx(calm.fuel_t_per_h)  # constant engine output
    loss = 1 - head.stw_m_s / calm.stw_m_s
    assert 0.05 < loss < 0.4  # Bf 8 head seas on a large container ship
    assert kwon.rpm_for_speed(head.stw_m_s, 0.0, storm) == pytest.approx(80.0, rel=1e-3)
