"""Calibration of the reference 4,600 TEU ship against the study's fixed-77-rpm voyage.

Reference study (seed 000, Table 11): 5,248 NM in about 300 h at a fixed 77 rpm on
684.8 t of fuel (with weather) -> 17.5 kn average and ~55 t/day.
"""


import pytest
from shiproute_core.units import M_S_PER_KNOT
from shiproute_planner.ship import PhysicsModel, SeaState, load_ship


@pytest.fixture(scope="module")
def calm77():
    return PhysicsModel(load_ship("container_4600teu")).evaluate(77.0, 0.0, SeaState.calm())


def test_speed_at_77_rpm(calm77):
    assert 17.5 <= float(calm77.stw_m_s) / M_S_PER_KNOT <= 18.0


def test_fuel_at_77_rpm(calm77):
    assert 50.0 <= float(calm77.fuel_t_per_h) * 24 <= 60.0


def test_reference_voyage_time_and_fuel(calm77):
    hours = 5248.0 / (float(calm77.stw_m_s) / M_S_PER_KNOT)
    assert hours == pytest.approx(300.0, rel=0.03)
    assert hours * float(calm77.fuel_t_per_h) == pytest.approx(684.8, rel=0.05)
