"""Wageningen B-series polynomials: term counts, published check values, efficiency shape.

The KQ term (s,t,u,v) = (0,6,2,2) is transcribed as -4.659e-4 and as -4.689e-4; we use
-4.659e-4 (Oosterveld & van Oossanen 1975 as tabulated by Bernitsas et al. 1981). Both
round to the published 10KQ(0) = 0.675 for B4-70 at P/D = 1 (the term contributes
7.84 c there), so the check value cannot discriminate; the test pins our choice.
"""

import numpy as np
import pytest
from shiproute_planner.ship import propeller


def test_term_counts():
    assert propeller._KT.shape == (propeller.KT_TERMS, 5) == (39, 5)
    assert propeller._KQ.shape == (propeller.KQ_TERMS, 5) == (47, 5)


def test_disputed_kq_term_value():
    row = [r for r in propeller._KQ if tuple(r[1:]) == (0, 6, 2, 2)]
    assert len(row) == 1 and row[0][0] == pytest.approx(-4.659e-4)


def test_b4_70_check_values_at_bollard():
    kt, kq = propeller.kt_kq(np.array([0.0]), pitch_ratio=1.0, area_ratio=0.70, blades=4)
    assert kt[0] == pytest.approx(0.4547, abs=5e-4)
    assert 10 * kq[0] == pytest.approx(0.675, abs=1e-3)


def test_b4_70_efficiency_curve_shape():
    j = np.linspace(0.05, 1.0, 400)
    kt, kq = propeller.kt_kq(j, 1.0, 0.70, 4)
    eta = kt * j / (2 * np.pi * kq)
    i = int(np.argmax(eta))
    assert 0.66 <= eta[i] <= 0.72
    assert 0.75 <= j[i] <= 0.95
    assert np.all(np.diff(kt) < 0) and np.all(np.diff(kq) < 0)
    assert np.all(np.diff(eta[:i]) > 0)


def test_zero_thrust_advance_ratio_is_near_pitch_ratio():
    curve = propeller.open_water_curve(1.0, 0.70, 4)
    assert 0.95 < curve.j_zero_thrust() < 1.15
    assert abs(curve.kt(np.array(curve.j_zero_thrust()))) < 1e-9
