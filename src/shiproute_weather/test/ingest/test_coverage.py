"""Time coverage: persistence beyond the forecast is bounded, then calm (missing), and the
hours of each are stated; a forecast that misses the voyage is refused."""

from __future__ import annotations

import numpy as np
import pytest
from shiproute_weather.contract import canonical as cv
from shiproute_weather.errors import ForecastCoverageError
from shiproute_weather.ingest.coverage import bounded_in_time, require_overlap, time_coverage
from shiproute_weather.sampling.sampler import ForecastSampler
from weather_fixtures import small_canonical


def test_persistence_is_bounded_then_calm() -> None:
    ds = small_canonical(n_time=5)  # 12 h of 3-hourly fields
    sampler = ForecastSampler(ds)
    t = cv.times_posix_s(ds)
    bounded = bounded_in_time(sampler, persistence_h=6.0)
    lon, lat = np.array([180.0]), np.array([37.0])
    last = sampler.sample(lon, lat, np.array([t[-1]]))[cv.WIND_U]
    held = bounded.sample(lon, lat, np.array([t[-1] + 5.9 * 3600]))[cv.WIND_U]
    after = bounded.sample(lon, lat, np.array([t[-1] + 6.1 * 3600]))[cv.WIND_U]
    before = bounded.sample(lon, lat, np.array([t[0] - 7 * 3600]))[cv.WIND_U]
    inside = bounded.sample(lon, lat, np.array([t[2] + 1800]))[cv.WIND_U]
    assert held == pytest.approx(last)
    assert np.isnan(after) and np.isnan(before)
    assert inside == pytest.approx(sampler.sample(lon, lat, np.array([t[2] + 1800]))[cv.WIND_U])
    # the bare sampler still clamps without limit (its documented contract)
    assert sampler.sample(lon, lat, np.array([t[-1] + 1e6]))[cv.WIND_U] == pytest.approx(last)


def test_hours_are_split_into_forecast_persistence_and_calm() -> None:
    times = np.array([0.0, 36 * 3600.0])
    cov = time_coverage(times, 0.0, 72 * 3600.0, persistence_h=24.0)
    assert (cov.forecast_h, cov.persistence_h, cov.calm_h) == (36.0, 24.0, 12.0)
    assert cov.covered_pct == pytest.approx(50.0)
    text = " ".join(cov.statements())
    assert "covers 36.0 h of the 72.0 h voyage (50 %)" in text and "12.0 h" in text
    assert time_coverage(times, 0.0, 36 * 3600.0).statements() == []


def test_a_forecast_from_another_year_is_refused() -> None:
    t2007 = np.array([1178755200.0, 1178776800.0])  # 2007-05-10 00Z and 06Z
    with pytest.raises(ForecastCoverageError, match=r"2007-05-10.*does not overlap.*2026"):
        require_overlap(t2007, 1772500000.0, 1773600000.0, "ecmwf_tigge.grb")


def test_a_monthly_climatology_follows_the_persistence() -> None:
    from datetime import UTC, datetime

    import xarray as xr

    ds = small_canonical(n_time=5)  # 2026-03-03 12Z .. 2026-03-04 00Z
    sampler = ForecastSampler(ds)
    months = np.array([f"2000-{m:02d}-15" for m in range(1, 13)], dtype="datetime64[ns]")
    shape = (12, ds.sizes["latitude"], ds.sizes["longitude"])
    clim = xr.Dataset({cv.WIND_U: (("time", "latitude", "longitude"),
                                   np.broadcast_to(np.arange(1.0, 13.0)[:, None, None],
                                                   shape).astype(np.float32))},
                      coords={"time": months, "latitude": ds["latitude"].values,
                              "longitude": ds["longitude"].values})
    t = cv.times_posix_s(ds)
    bounded = bounded_in_time(sampler, 6.0, clim, until_s=t[-1] + 60 * 86400.0)
    lon, lat = np.array([180.0]), np.array([37.0])
    mid_april = datetime(2026, 4, 15, tzinfo=UTC).timestamp()
    mid_may = datetime(2026, 5, 15, tzinfo=UTC).timestamp()
    assert bounded.sample(lon, lat, np.array([mid_april]))[cv.WIND_U] == pytest.approx(4.0)
    half = bounded.sample(lon, lat, np.array([(mid_april + mid_may) / 2]))[cv.WIND_U]
    assert half == pytest.approx(4.5)  # monthly means interpolated linearly
    # right after the persistence: March's value; the persistence itself is untouched
    assert bounded.sample(lon, lat, np.array([t[-1] + 6.5 * 3600]))[cv.WIND_U] == \
        pytest.approx(3.0, abs=0.01)
    last = sampler.sample(lon, lat, np.array([t[-1]]))[cv.WIND_U]
    assert bounded.sample(lon, lat, np.array([t[-1] + 5 * 3600]))[cv.WIND_U] == \
        pytest.approx(last)
    # fields the climatology lacks are calm (missing) beyond the persistence
    assert np.isnan(bounded.sample(lon, lat, np.array([mid_april]))[cv.WAVE_HS])
    cov = time_coverage(t, t[0], mid_may, 6.0, climatology="clim.nc")
    assert any("monthly climatology (clim.nc)" in s for s in cov.statements())
