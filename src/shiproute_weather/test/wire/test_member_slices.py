"""Members on the wire: a cycle of M members and T valid times is M x T slices (slice_index =
member x T + t), split and joined losslessly (float32) or within the 16-bit packing's step;
the cycle builder keeps an ensemble within the slice budget and says what it cut."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from member_fixtures import perturbed_members
from shiproute_weather.contract import canonical as cv
from shiproute_weather.contract.members import member_count, member_labels
from shiproute_weather.errors import SliceError
from shiproute_weather.ingest.cycle_builder import CycleConfig, thin
from shiproute_weather.wire.packing import pack_field
from shiproute_weather.wire.slices import cycle_info, dataset_to_slices, slices_to_dataset
from weather_fixtures import small_canonical


def _three():
    return perturbed_members(small_canonical(n_time=4), 3)


def test_three_member_cycle_splits_into_member_major_slices() -> None:
    ds = _three()
    slices = list(dataset_to_slices(ds))
    assert len(slices) == 12
    assert [(s.slice_index, s.member, s.member_label) for s in slices[3:5]] == [
        (3, 0, "0"), (4, 1, "1")]
    assert all(s.slice_count == 12 and s.member_count == 3 for s in slices)
    info = cycle_info(ds)
    assert (info.slice_count, info.member_count, info.member_labels, info.member_kind) == (
        12, 3, ("0", "1", "2"), "ensemble")
    assert info.first_valid_time_ns < info.last_valid_time_ns  # each member's time axis


def test_three_member_round_trip_is_exact_in_float32() -> None:
    ds = _three()
    back = slices_to_dataset(list(reversed(list(dataset_to_slices(ds)))))
    assert member_count(back) == 3 and member_labels(back) == ("0", "1", "2")
    assert back.attrs["member_kind"] == "ensemble"
    for n in cv.present_variables(ds):
        np.testing.assert_array_equal(back[n].values, ds[n].values)
    np.testing.assert_array_equal(back["time"].values, ds["time"].values)


def test_three_member_round_trip_packed16_within_half_a_step() -> None:
    """16-bit simple packing: value = offset + scale x code with scale = (max - min) / 65534,
    rounded to the nearest code, so each decoded value is within scale / 2 of the original
    (plus one float32 rounding of the decoded value)."""
    ds = _three()
    slices, scales = [], {}
    for s in dataset_to_slices(ds):
        packed = tuple(dataclasses.replace(f, data=pack_field(f.data, f.name)) for f in s.fields)
        scales.update({(s.slice_index, f.name): f.data.scale_factor for f in packed})
        slices.append(dataclasses.replace(s, fields=packed))
    back = slices_to_dataset(slices)
    n_t = ds.sizes["time"]
    for (index, name), scale in scales.items():
        m, k = divmod(index, n_t)
        a = back[name].values[m, k].astype(np.float64)
        b = ds[name].values[m, k].astype(np.float64)
        assert np.array_equal(np.isnan(a), np.isnan(b))
        ok = ~np.isnan(b)
        bound = scale / 2 * (1 + 1e-9) + np.spacing(np.abs(b[ok]).astype(np.float32))
        assert np.all(np.abs(a[ok] - b[ok]) <= bound), (index, name)
        assert scale < 1e-3 * max(1.0, float(np.nanmax(np.abs(b))))  # 16 bits: a fine step


def test_member_count_mismatch_across_slices_is_refused() -> None:
    slices = list(dataset_to_slices(_three()))
    slices[7] = dataclasses.replace(slices[7], member_count=2)
    with pytest.raises(SliceError, match=r"slice 7 says 2 members.*member count mismatch"):
        slices_to_dataset(slices)
    slices = list(dataset_to_slices(_three()))
    slices[5] = dataclasses.replace(slices[5], member_label="x")  # one slice of member 1
    with pytest.raises(SliceError, match=r"member 1 labelled '1' and 'x'"):
        slices_to_dataset(slices)
    slices = [dataclasses.replace(s, member_label="0") if s.member == 1 else s
              for s in dataset_to_slices(_three())]
    with pytest.raises(Exception, match=r"member labels \['0'\] appear more than once"):
        slices_to_dataset(slices)
    with pytest.raises(SliceError, match=r"expected 0\.\.11"):
        slices_to_dataset(list(dataset_to_slices(_three()))[:-1])


def test_twenty_member_cycle_is_kept_within_the_slice_budget() -> None:
    """A 20-member cycle of 8 valid times (3-hourly) is 160 slices: within max_slices 200 as it
    is; with max_slices 100 (5 per member) every 2nd valid time is kept, 6 h apart, and the
    last kept time is still 18 h on (the horizon); with max_members 5 the first 5 members are
    kept whole. Each cut is stated."""
    ds = perturbed_members(small_canonical(n_time=8), 20)
    kept, notes = thin(ds, CycleConfig(max_slices=200))
    assert member_count(kept) == 20 and kept.sizes["time"] == 8 and not notes
    kept, notes = thin(ds, CycleConfig(max_slices=100))
    assert member_count(kept) == 20 and kept.sizes["time"] == 4
    assert np.array_equal(kept["time"].values, ds["time"].values[::2])
    assert any("one valid time in 2 kept (4 per member, 6 h apart" in n for n in notes)
    kept, notes = thin(ds, CycleConfig(max_members=5))
    assert member_labels(kept) == ("0", "1", "2", "3", "4") and kept.sizes["time"] == 8
    assert any("15 of 20 members dropped (max_members 5)" in n for n in notes)
    assert len(list(dataset_to_slices(kept))) == 40
