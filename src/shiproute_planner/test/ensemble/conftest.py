"""Synthetic ensembles for the member-evaluation tests: North Pacific grids whose members
differ only in wind and waves."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

REF = "2026-03-03T12:00:00"


def ensemble(winds_m_s: list[float], hs_m: list[float]) -> xr.Dataset:
    """Members with uniform wind blowing towards the east at `winds_m_s` (negative: from the
    east) and total sea `hs_m` coming from where the wind comes from; 1 deg, 6-hourly, 16 d."""
    lat = np.arange(10.0, 62.0 + 1e-9, 1.0)
    lon = np.arange(115.0, 245.0 + 1e-9, 1.0)
    time = np.datetime64(REF, "ns") + np.arange(65) * np.timedelta64(6, "h")
    shape = (len(winds_m_s), time.size, lat.size, lon.size)
    u = np.stack([np.full(shape[1:], w, dtype=np.float32) for w in winds_m_s])
    hs = np.stack([np.full(shape[1:], h, dtype=np.float32) for h in hs_m])
    wave_from = np.stack([np.full(shape[1:], 270.0 if w >= 0 else 90.0, dtype=np.float32)
                          for w in winds_m_s])
    dims = ("member", "time", "latitude", "longitude")
    return xr.Dataset(
        {"eastward_wind": (dims, u), "northward_wind": (dims, np.zeros(shape, np.float32)),
         "sea_surface_wave_significant_height": (dims, hs),
         "sea_surface_wave_from_direction": (dims, wave_from),
         "sea_surface_wave_mean_period": (dims, np.full(shape, 8.0, np.float32))},
        coords={"member": np.arange(len(winds_m_s), dtype=np.int64), "time": time,
                "latitude": lat, "longitude": lon,
                "member_label": ("member", [f"m{k}" for k in range(len(winds_m_s))])},
        attrs={"forecast_reference_time": REF + "Z", "source": "test ensemble",
               "cycle_id": "test-ens", "member_kind": "ensemble"})


@pytest.fixture(scope="session")
def two_members() -> xr.Dataset:
    """Member 0: 5 m/s westerly, 1.5 m sea; member 1: 18 m/s easterly, 5 m sea."""
    return ensemble([5.0, -18.0], [1.5, 5.0])


@pytest.fixture(scope="session")
def over_limit_members() -> xr.Dataset:
    """Member 0: 5 m/s westerly, 1.5 m sea; member 1: 18 m/s westerly, 9 m sea (above the
    4,600 TEU ship's 8 m limit)."""
    return ensemble([5.0, 18.0], [1.5, 9.0])


@pytest.fixture(scope="session")
def head_sea_forecast() -> xr.Dataset:
    """One deterministic forecast: 12 m/s from the east, 4 m sea from the east, everywhere."""
    return ensemble([-12.0], [4.0]).isel(member=0).drop_vars("member_label")
