"""Holtrop & Mennen (1982) published worked example: every listed component within 1 %."""


import numpy as np
import pytest
from shiproute_core.units import M_S_PER_KNOT
from shiproute_planner.ship.holtrop_mennen import HMHull, coefficients, resistance

# Holtrop & Mennen (1982), ISP 29(335), numerical example (single-screw ship at 25 kn)
EXAMPLE = HMHull(
    lwl_m=205.0, breadth_m=32.0, draft_fore_m=10.0, draft_aft_m=10.0, volume_m3=37500.0,
    midship_coefficient=0.98, waterplane_coefficient=0.75, lcb_percent=-0.75,
    bulb_area_m2=20.0, bulb_center_height_m=4.0, transom_area_m2=16.0, appendage_area_m2=50.0,
    appendage_form_factor=1.5, stern_shape_coefficient=10.0, wetted_surface_m2=7381.45,
    propeller_diameter_m=8.0, propeller_area_ratio=0.75,
)
RHO, NU = 1025.0, 1.1883e-6


def _result():
    c = coefficients(EXAMPLE)
    r = resistance(EXAMPLE, c, np.array([25.0 * M_S_PER_KNOT]), RHO, NU)
    return c, r


@pytest.mark.parametrize(
    ("name", "published"),
    [("cp", 0.5833), ("form_factor", 1.156), ("c1", 1.398), ("m1", -2.1274), ("lam", 0.6513)],
)
def test_coefficients_match_worked_example(name, published):
    c, _ = _result()
    assert getattr(c, name) == pytest.approx(published, rel=0.01)


@pytest.mark.parametrize(
    ("name", "published_kn"),
    [("r_friction_n", 869.63), ("r_wave_n", 557.11), ("r_correlation_n", 221.98)],
)
def test_resistance_components_match_worked_example(name, published_kn):
    _, r = _result()
    assert float(getattr(r, name)[0]) / 1000.0 == pytest.approx(published_kn, rel=0.01)


def test_froude_number_and_wetted_surface_estimate():
    _, r = _result()
    assert float(r.froude[0]) == pytest.approx(0.2868, rel=0.01)
    estimated = coefficients(
        HMHull(**{**EXAMPLE.__dict__, "wetted_surface_m2": None})
    ).wetted_surface_m2
    assert estimated == pytest.approx(7381.45, rel=0.01)  # Holtrop's S regression, same ship


def test_resistance_grows_with_speed_and_propulsion_factors_are_plausible():
    c = coefficients(EXAMPLE)
    v = np.linspace(3.0, 13.0, 30)
    r = resistance(EXAMPLE, c, v, RHO, NU)
    assert np.all(np.diff(r.r_total_n) > 0)
    assert 0.1 < c.thrust_deduction < 0.3
    assert np.all((r.wake_fraction > 0.15) & (r.wake_fraction < 0.45))
    assert 0.95 < c.eta_r < 1.05
