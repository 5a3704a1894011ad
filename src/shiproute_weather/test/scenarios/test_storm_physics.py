"""Storm physics of the scenario generator (Holland wind, dispersive swell) against published
values."""

from __future__ import annotations

import math

import numpy as np
import pytest
from shiproute_core.units import S_PER_HOUR
from shiproute_weather.physics.wave_growth import G
from shiproute_weather.scenarios.swell import distances_and_bearings, radiate
from shiproute_weather.scenarios.synth_wind import RHO_AIR, holland_gradient_wind_m_s


def test_holland_profile_peaks_at_radius_of_maximum_wind() -> None:
    r = np.linspace(10e3, 1500e3, 3000)
    v = holland_gradient_wind_m_s(r, 4000.0, 300e3, 1.3, 0.0)
    assert r[np.argmax(v)] == pytest.approx(300e3, rel=0.01)
    # Holland (1980): V_max = sqrt(B dp / (rho e)) without Coriolis
    assert v.max() == pytest.approx(math.sqrt(1.3 * 4000.0 / (RHO_AIR * math.e)), rel=1e-4)
    with_f = holland_gradient_wind_m_s(r, 4000.0, 300e3, 1.3, 1e-4)
    assert np.all(with_f < v)


def test_swell_arrives_dispersively_from_the_source() -> None:
    lat = np.array([30.0, 40.0])
    lon = np.array([160.0, 170.0, 180.0])
    dist, brg = distances_and_bearings(np.array([40.0]), np.array([150.0]), lat, lon)
    times = np.arange(0.0, 73.0, 3.0)
    e, es, ec, eot = radiate(times, np.array([0.0]), np.array([10.0]), np.array([14.0]),
                             np.array([90.0]), np.array([300e3]), dist, brg, 3.0)
    iy, ix = 1, 2  # (40 N, 180 E), ~2,550 km east of the source
    k = int(np.argmax(e[:, iy, ix]))
    period = e[k, iy, ix] / eot[k, iy, ix]
    # deep water: the 14 s group travels at g T / (4 pi) = 10.9 m/s -> ~65 h for 2,550 km
    age_h = 4 * math.pi * dist[0, iy, ix] / (G * period) / S_PER_HOUR
    assert times[k] == pytest.approx(age_h, abs=3.0)
    assert period == pytest.approx(14.0, rel=0.15)
    from_deg = math.degrees(math.atan2(es[k, iy, ix], ec[k, iy, ix])) % 360.0
    assert from_deg == pytest.approx(brg[0, iy, ix], abs=0.5)  # comes from the source (west)
    assert 250.0 < from_deg < 300.0
