"""Wave physics shared by ingest and scenarios (periods, growth), against published values."""

from __future__ import annotations

import math

import numpy as np
import pytest
from shiproute_weather.physics.spectral import period_over_tp, to_tm01_factor
from shiproute_weather.physics.wave_growth import G, grow_step


def test_pierson_moskowitz_and_jonswap_period_ratios() -> None:
    # DNV-RP-C205 (2010) 3.5.5: Pierson-Moskowitz Tz = 0.710 Tp and T1 = 0.772 Tp;
    # JONSWAP gamma 3.3: T1 = 0.834 Tp
    assert period_over_tp("tm02", 1.0) == pytest.approx(0.710, abs=0.002)
    assert period_over_tp("tm01", 1.0) == pytest.approx(0.772, abs=0.002)
    assert period_over_tp("tm01", 3.3) == pytest.approx(0.834, abs=0.004)
    assert to_tm01_factor("tm01") == 1.0
    assert to_tm01_factor("tm_10") < 1.0 < to_tm01_factor("tm02")  # Tm02 < Tm01 < Tm-1,0


def test_wind_sea_reaches_pierson_moskowitz_limit() -> None:
    u = np.array([10.0, 20.0])
    hs = np.zeros(2)
    for _ in range(200):  # 200 x 3 h of steady wind over unlimited fetch
        hs, tp = grow_step(hs, np.zeros(2), u, np.zeros(2), np.full(2, 5e6), 3 * 3600.0)
    # PM: g Hs / U^2 = 0.241 (dimensionless energy 3.64e-3): 2.46 m at 10 m/s, 9.83 m at 20
    np.testing.assert_allclose(hs, 0.241 * u ** 2 / G, rtol=1e-3)
    assert np.all(np.diff(tp) > 0) and 7.0 < tp[0] < 9.0


def test_fetch_limited_jonswap_growth() -> None:
    # U = 10 m/s over 100 km for a long time: JONSWAP gHs/U^2 = 1.6e-3 (gF/U^2)^0.5 -> 1.62 m
    hs = np.zeros(1)
    for _ in range(40):
        hs, _tp = grow_step(hs, np.zeros(1), np.array([10.0]), np.zeros(1),
                           np.array([100e3]), 3 * 3600.0)
    chi = G * 100e3 / 100.0
    assert hs[0] == pytest.approx(1.6e-3 * math.sqrt(chi) * 100.0 / G, rel=1e-6)
    assert hs[0] == pytest.approx(1.62, abs=0.01)
    # a wind turning by 90 deg leaves no wind sea to carry over
    turned, _ = grow_step(hs, np.zeros(1), np.array([10.0]), np.array([90.0]),
                          np.array([100e3]), 1.0)
    assert turned[0] < 0.05
