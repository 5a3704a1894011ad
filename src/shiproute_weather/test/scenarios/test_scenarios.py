"""Bundled scenarios: deterministic, physically plausible, the storm crosses the route."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from shiproute_weather.contract import canonical as cv
from shiproute_weather.scenarios.catalogue import (
    FORMAT_VERSION,
    SCENARIOS,
    scenario_dataset,
    scenario_path,
)
from shiproute_weather.scenarios.fields import build_fields
from shiproute_weather.scenarios.synth_seas import MARCH_SWELL
from shiproute_weather.scenarios.synth_wind import MARCH

BUSAN = (35.08, 129.11)
LONG_BEACH = (33.69, -118.25)
EARTH_RADIUS_KM = 6371.0


def _unit(lat_deg: np.ndarray, lon_deg: np.ndarray) -> np.ndarray:
    la, lo = np.deg2rad(lat_deg), np.deg2rad(lon_deg)
    return np.stack([np.cos(la) * np.cos(lo), np.cos(la) * np.sin(lo), np.sin(la)], axis=-1)


def great_circle(a: tuple[float, float], b: tuple[float, float], n: int) -> np.ndarray:
    """(n, 3) unit vectors along the great circle from a to b (spherical interpolation)."""
    pa, pb = _unit(np.array(a[0]), np.array(a[1])), _unit(np.array(b[0]), np.array(b[1]))
    omega = np.arccos(np.clip(pa @ pb, -1, 1))
    f = np.linspace(0, 1, n)[:, None]
    return (np.sin((1 - f) * omega) * pa + np.sin(f * omega) * pb) / np.sin(omega)


def test_generation_is_deterministic() -> None:
    lat = np.arange(30.0, 40.1, 2.0)
    lon = np.arange(140.0, 180.1, 2.0)
    hours = np.arange(60.0, 120.1, 3.0)
    spec = SCENARIOS["storm_march"]
    a = build_fields(MARCH, MARCH_SWELL, spec.track, np.random.default_rng(5), lat, lon, hours)
    b = build_fields(MARCH, MARCH_SWELL, spec.track, np.random.default_rng(5), lat, lon, hours)
    for n in a:
        np.testing.assert_array_equal(a[n], b[n], err_msg=n)


@pytest.fixture(scope="module")
def storm(tmp_path_factory: pytest.TempPathFactory):
    mp = pytest.MonkeyPatch()
    data = tmp_path_factory.mktemp("data")
    (data / "scenarios").mkdir()
    for stale in ("storm_march.v0.nc", "storm_march_cycle2.v0.nc"):  # older cache versions
        (data / "scenarios" / stale).write_bytes(b"CDF\x01")
    mp.setenv("SHIPROUTE_DATA_DIR", str(data))
    try:
        yield scenario_dataset("storm_march")
    finally:
        mp.undo()


@pytest.mark.slow
def test_storm_scenario_file_and_ranges(storm) -> None:
    path = scenario_path("storm_march")
    # generating replaced the scenario's older cache version, not another scenario's
    assert sorted(p.name for p in Path(path).parent.iterdir()) == [
        f"storm_march.v{FORMAT_VERSION}.nc", "storm_march_cycle2.v0.nc"]
    # uncompressed float32 cache: the data bytes plus a small HDF5 header, nothing more
    data_bytes = len(cv.CANONICAL_ORDER) * 129 * 105 * 261 * 4
    assert data_bytes <= Path(path).stat().st_size < data_bytes + 1_000_000
    assert storm.sizes == {"time": 129, "latitude": 105, "longitude": 261}
    assert storm.attrs["forecast_reference_time"] == "2026-03-03T12:00:00Z"
    assert set(storm.data_vars) == set(cv.CANONICAL_ORDER)
    for name in cv.DIRECTION_VARIABLES:  # stored directions wrap into [0, 360)
        assert float(storm[name].min()) >= 0.0 and float(storm[name].max()) < 360.0, name
    speed = np.hypot(storm[cv.WIND_U], storm[cv.WIND_V])
    assert 20.0 < float(speed.max()) < 40.0  # storm force, not a super typhoon
    assert 6.0 < float(speed.mean()) < 11.0  # winter North Pacific mean 10 m wind
    hs = storm[cv.WAVE_HS]
    assert 8.0 < float(hs.max()) < 20.0 and float(hs.min()) >= 0.0
    current = np.hypot(storm[cv.CURRENT_U], storm[cv.CURRENT_V])
    assert float(current.max()) < 2.0
    # Kuroshio core south of Japan flows east-north-east at ~1 m/s or more
    assert float(storm[cv.CURRENT_U].sel(latitude=34.5, longitude=140.5).isel(time=0)) > 0.5
    # land: no waves, no currents; wind defined
    inland = storm.sel(latitude=36.0, longitude=138.0).isel(time=0)
    assert np.isnan(float(inland[cv.WAVE_HS])) and np.isnan(float(inland[cv.CURRENT_U]))
    assert np.isfinite(float(inland[cv.WIND_U]))
    # total sea combines the partitions in quadrature
    tot = storm[cv.WAVE_HS].values
    parts = np.hypot(storm[cv.WIND_WAVE_HS].values, storm[cv.SWELL_HS].values)
    ok = np.isfinite(tot)
    # each of the three is rounded to 0.01 m: |error| <= 0.005 (1 + sqrt(2))
    np.testing.assert_allclose(tot[ok], parts[ok], atol=0.0121)


@pytest.mark.slow
def test_storm_crosses_the_great_circle_during_the_voyage(storm) -> None:
    gc = great_circle(BUSAN, LONG_BEACH, 400)
    dep = np.datetime64("2026-03-03T18:00")
    rta = dep + np.timedelta64(13, "D")
    speed = np.hypot(storm[cv.WIND_U], storm[cv.WIND_V])
    closest_km = []
    for t in storm.time.values:
        if not (dep <= t <= rta):
            continue
        s = speed.sel(time=t)
        if float(s.max()) < 20.0:
            continue
        iy, ix = np.unravel_index(int(np.argmax(s.values)), s.shape)
        lat_c, lon_c = float(storm.latitude[iy]), float(storm.longitude[ix])
        cos_d = np.clip(gc @ _unit(np.array(lat_c), np.array(lon_c)), -1, 1)
        closest_km.append(float(np.arccos(cos_d).min()) * EARTH_RADIUS_KM)
    assert closest_km and min(closest_km) < 300.0


@pytest.mark.slow
def test_second_cycle_is_later_and_shifted(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                           storm) -> None:
    monkeypatch.setenv("SHIPROUTE_DATA_DIR", str(tmp_path))
    c2 = scenario_dataset("storm_march_cycle2")
    assert c2.attrs["forecast_reference_time"] == "2026-03-03T18:00:00Z"
    assert str(c2.time.values[0])[:13] == "2026-03-03T18"
    t = np.datetime64("2026-03-08T12:00", "ns")
    a = np.hypot(storm[cv.WIND_U], storm[cv.WIND_V]).sel(time=t)
    b = np.hypot(c2[cv.WIND_U], c2[cv.WIND_V]).sel(time=t)
    ia = np.unravel_index(int(np.argmax(a.values)), a.shape)
    ib = np.unravel_index(int(np.argmax(b.values)), b.shape)
    assert ia != ib  # storm position differs between the cycles
    far = dict(latitude=15.0, longitude=230.0)  # the rest of the ocean is the same weather
    assert float(a.sel(**far)) == pytest.approx(float(b.sel(**far)), abs=0.05)
