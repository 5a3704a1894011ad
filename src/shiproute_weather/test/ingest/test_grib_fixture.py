"""A generated ECMWF-style GRIB2 file: several hypercubes, model runs x steps, overlaps."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from shiproute_weather.contract import canonical as cv
from shiproute_weather.ingest.loaders import open_forecast

eccodes = pytest.importorskip("eccodes")


def _write(path: Path, fields: list[tuple[str, str, int, int, int, float]]) -> Path:
    with path.open("wb") as f:
        for short, tol, level, hour, step, value in fields:
            h = eccodes.codes_grib_new_from_samples("regular_ll_sfc_grib2")
            eccodes.codes_set(h, "centre", "ecmf")
            eccodes.codes_set_key_vals(h, {
                "Ni": 8, "Nj": 5, "latitudeOfFirstGridPointInDegrees": 40.0,
                "longitudeOfFirstGridPointInDegrees": 176.0,
                "latitudeOfLastGridPointInDegrees": 36.0,
                "longitudeOfLastGridPointInDegrees": 183.0,
                "iDirectionIncrementInDegrees": 1.0, "jDirectionIncrementInDegrees": 1.0})
            eccodes.codes_set(h, "dataDate", 20260303)
            eccodes.codes_set(h, "dataTime", hour * 100)
            eccodes.codes_set(h, "stepRange", step)
            eccodes.codes_set(h, "typeOfLevel", tol)
            eccodes.codes_set(h, "level", level)
            eccodes.codes_set(h, "shortName", short)
            eccodes.codes_set_values(h, np.full(40, value, dtype=float))
            eccodes.codes_write(h, f)
            eccodes.codes_release(h)
    return path


def test_runs_steps_levels_and_antimeridian(tmp_path: Path) -> None:
    fields = []
    for hour in (0, 12):
        for step in (0, 6, 12):
            fields += [("10u", "heightAboveGround", 10, hour, step, hour / 2 + step),
                       ("10v", "heightAboveGround", 10, hour, step, -1.0),
                       ("swh", "surface", 0, hour, step, 2.0 + step / 6),
                       ("u", "isobaricInhPa", 500, hour, step, 40.0)]  # not a 10 m wind
    for hour, step in ((0, 0), (12, 12)):
        fields.append(("u", "heightAboveGround", 100, hour, step, 55.0))  # 100 m: ignored
    ds = open_forecast([_write(tmp_path / "ecmwf.grib2", fields)])
    assert set(ds.data_vars) == {cv.WIND_U, cv.WIND_V, cv.WAVE_HS}
    hours = (ds.time.values - np.datetime64("2026-03-03T00:00")) / np.timedelta64(1, "h")
    np.testing.assert_array_equal(hours, [0, 6, 12, 18, 24])
    # valid 12 UTC exists in both runs (00 + 12 h, 12 + 0 h): the later run wins
    np.testing.assert_array_equal(ds[cv.WIND_U].values[:, 0, 0], [0, 6, 6, 12, 18])
    assert ds.attrs["forecast_reference_time"] == "2026-03-03T00:00:00Z"
    assert ds.longitude.values[0] == 176.0 and ds.longitude.values[-1] == 183.0
    assert ds.latitude.values[0] == 36.0
