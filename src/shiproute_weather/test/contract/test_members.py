"""The member part of the canonical contract: helpers, validation, refusals naming the input."""

from __future__ import annotations

import numpy as np
import pytest
from shiproute_weather.contract import canonical as cv
from shiproute_weather.contract.members import (
    ensemble_mean,
    member_count,
    member_labels,
    select_member,
    stack_members,
)
from shiproute_weather.contract.validate import validate
from shiproute_weather.errors import GridError
from weather_fixtures import small_canonical


def _two() -> tuple:
    a = small_canonical(n_time=3)
    b = a.copy(deep=True)
    b[cv.WIND_U].values += 4.0
    b[cv.WAVE_DIR].values = (a[cv.WAVE_DIR].values + 20.0) % 360.0
    return a, b


def test_stack_select_and_mean_are_consistent() -> None:
    a, b = _two()
    ds = validate(stack_members([a, b], ["gfs", "ecmwf"], kind="multi-model"), "stacked")
    assert member_count(ds) == 2 and member_labels(ds) == ("gfs", "ecmwf")
    assert ds[cv.WIND_U].dims == ("member", "time", "latitude", "longitude")
    assert ds["member"].dtype == np.int64 and list(ds["member"].values) == [0, 1]
    assert ds.attrs["member_kind"] == "multi-model"
    one = select_member(ds, 1)
    assert "member" not in one.dims and one.attrs["member_label"] == "ecmwf"
    np.testing.assert_array_equal(one[cv.WIND_U].values, b[cv.WIND_U].values)
    mean = ensemble_mean(ds)
    # scalar: arithmetic mean (+2 m/s); direction: mean of unit vectors (+10 deg, no wrap at 0)
    np.testing.assert_allclose(mean[cv.WIND_U].values, a[cv.WIND_U].values + 2.0, atol=1e-5)
    d = (mean[cv.WAVE_DIR].values - a[cv.WAVE_DIR].values) % 360.0
    ok = np.isfinite(d)
    np.testing.assert_allclose(d[ok], 10.0, atol=1e-3)
    assert member_count(a) == 1 and ensemble_mean(a) is a


def test_duplicate_labels_are_refused_with_the_label() -> None:
    a, b = _two()
    with pytest.raises(GridError, match=r"member labels \['gfs'\] appear more than once"):
        stack_members([a, b], ["gfs", "gfs"], kind="multi-model")
    ds = stack_members([a, b], ["x", "y"])
    ds = ds.assign_coords(member_label=("member", np.array(["x", "x"], dtype=object)))
    with pytest.raises(GridError, match=r"bad\.nc: member labels \['x'\]"):
        validate(ds, "bad.nc")


def test_validate_checks_every_member_and_the_kind() -> None:
    a, b = _two()
    b[cv.WAVE_HS].values[0, 0, -1] = 45.0  # only member 1 is impossible
    ds = stack_members([a, b], ["0", "1"])
    with pytest.raises(Exception, match=r"sea_surface_wave_significant_height.*45"):
        validate(ds, "ens")
    a, b = _two()
    ds = stack_members([a, b])
    ds.attrs["member_kind"] = "lucky"
    with pytest.raises(GridError, match=r"member_kind.*'lucky'"):
        validate(ds, "ens")
    with pytest.raises(GridError, match=r"member 2 outside 0\.\.1"):
        select_member(stack_members([a, b]), 2)


def test_members_on_other_grids_cannot_be_stacked() -> None:
    a = small_canonical(n_time=3)
    b = small_canonical(n_time=3, lat=(30.0, 40.0, 1.0))
    with pytest.raises(GridError, match=r"member '1'.*latitude axis differs"):
        stack_members([a, b])
