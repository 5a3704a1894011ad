"""The numpy regridder used when combining files gives the sampler's trilinear values (the
reference tested against brute force in test_sampler), NaN pattern included."""

from __future__ import annotations

import numpy as np
from shiproute_weather.ingest.combine import resample
from shiproute_weather.ingest.regrid import regrid
from weather_fixtures import small_canonical


def test_regrid_equals_the_sampler_across_the_antimeridian() -> None:
    ds = small_canonical(n_time=5, lon=(170.0, 195.0, 0.5))
    lat = np.arange(29.9, 40.3, 0.7)  # reaches beyond the source rows: NaN there
    lon = np.arange(-192.0, -163.0, 0.9)  # another longitude frame, beyond both ends
    t = ds.time.values[0] + np.arange(-2, 15, 2) * np.timedelta64(1, "h")
    ref, got = resample(ds, lat, lon, t), regrid(ds, lat, lon, t)
    for n in ref.data_vars:
        x, y = ref[n].values, got[n].values
        assert np.array_equal(np.isnan(x), np.isnan(y)), n
        diff = (x - y + 180.0) % 360.0 - 180.0 if "direction" in n else x - y
        assert np.nanmax(np.abs(diff)) < 1e-3, n
