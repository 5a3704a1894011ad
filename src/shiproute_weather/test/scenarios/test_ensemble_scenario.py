"""The ensemble storm scenario: members spread like medium-range ensembles' cyclones, and the
bundled dataset carries every member through the catalogue."""

from __future__ import annotations

import numpy as np
import pytest
from shiproute_core.geodesy import inverse
from shiproute_weather.scenarios.catalogue import ENSEMBLES, SCENARIOS, scenario_names
from shiproute_weather.scenarios.ensemble import member_draws, perturbed_track

NAME = "storm_march_ensemble"


def _centre_at(track, hours: float) -> tuple[float, float]:
    """Storm centre (lon, lat) at `hours` by linear interpolation along the track."""
    h = np.array([p.hours for p in track])
    return (float(np.interp(hours, h, [p.lon_deg for p in track])),
            float(np.interp(hours, h, [p.lat_deg for p in track])))


def test_member_storms_spread_as_ensemble_cyclone_positions_grow():
    spec = ENSEMBLES[NAME]
    base = SCENARIOS[spec.base]
    z = member_draws(200, spec.seed)  # many draws: the spread's statistics, not the 20 samples
    tracks = [perturbed_track(base.track, z[k], 0.0) for k in range(z.shape[0])]
    assert perturbed_track(base.track, z[0], 0.0) == base.track  # member 0 is the control
    rms_km = {}
    for day in (2.5, 3.0, 5.0):
        h = day * 24.0
        c_lon, c_lat = _centre_at(base.track, h)
        pts = np.array([_centre_at(t, h) for t in tracks[1:]])
        _, d = inverse(np.full(len(pts), c_lon), np.full(len(pts), c_lat), pts[:, 0], pts[:, 1])
        rms_km[day] = float(np.sqrt(np.mean(d**2))) / 1000.0
    # a calibrated ensemble's spread matches its error: ECMWF's cyclone position errors are
    # < 200 km at day 3 and < 350 km at day 5 ("Known IFS forecasting issues"); the members'
    # RMS distance from the control should be of that size and grow with lead time
    assert 100.0 < rms_km[3.0] < 250.0
    assert 200.0 < rms_km[5.0] < 450.0
    assert rms_km[2.5] < rms_km[3.0] < rms_km[5.0]


def test_intensity_spread_grows_and_stays_bounded():
    spec = ENSEMBLES[NAME]
    base = SCENARIOS[spec.base]
    z = member_draws(200, spec.seed)
    ratios = np.array([[m.dp_hpa / b.dp_hpa for m, b in zip(
        perturbed_track(base.track, z[k], 0.0), base.track, strict=True)]
        for k in range(1, z.shape[0])])
    spread = ratios.std(axis=0)
    assert np.all(np.diff(spread) > 0)  # later track points: larger spread
    assert ratios.min() >= np.exp(-0.35) - 1e-9 and ratios.max() <= np.exp(0.35) + 1e-9


@pytest.mark.slow
def test_bundled_ensemble_has_twenty_members_that_differ():
    from shiproute_weather.scenarios.catalogue import scenario_dataset

    assert NAME in scenario_names()
    ds = scenario_dataset(NAME)
    assert ds.sizes["member"] == 20 and ds.attrs["member_kind"] == "ensemble"
    assert list(ds["member"].values) == list(range(20))
    assert ds["member_label"].values[0] == "control"
    hs = ds["sea_surface_wave_significant_height"]
    peak = hs.max(dim=("latitude", "longitude"))
    # members agree at the start (only the storm is perturbed, spread 0 at lead 0) ...
    assert float(peak.isel(time=0).std()) < 0.05
    # ... and differ days later (each member's own storm)
    assert float(peak.isel(time=slice(16, 30)).std(dim="member").max()) > 0.3
