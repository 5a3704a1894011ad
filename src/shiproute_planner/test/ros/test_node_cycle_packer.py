"""The planner node's forecast intake (ROS-free parts): slices (float32 or 16-bit packed fields)
packed into the sampler as they arrive, the time window kept behind the ship, bad cycles
rejected, the slice-buffer DDS profile."""

from __future__ import annotations

import functools

import numpy as np
import pytest
from shiproute_planner.errors import ForecastCycleError
from shiproute_planner.ros.cycle_assembler import CycleAssembler
from shiproute_planner.ros.cycle_packer import KEEP_BEHIND_S, CyclePacker, SliceFields, hs_field_at


@functools.lru_cache(maxsize=2)
def _cycle(encoding: str = "packed16"):
    """Eight valid times (3-hourly) of the bundled storm forecast and their slice messages."""
    from shiproute_weather.ros.convert import dataset_to_msgs
    from shiproute_weather.scenarios.catalogue import scenario_dataset

    ds = scenario_dataset("storm_march").isel(time=slice(0, 8)).load()
    ds.attrs["cycle_id"] = "packer-test"
    return ds, dataset_to_msgs(ds, encoding=encoding)[1]


def _fields(encoding: str = "packed16"):
    from shiproute_planner.ros.convert import slice_fields

    return [slice_fields(m) for m in _cycle(encoding)[1]]


def test_slice_fields_are_views_on_the_message_buffers():
    from shiproute_weather.wire.packing import PackedField, unpack_field

    ds, msgs = _cycle("float32")
    s = _fields("float32")[3]
    assert (s.cycle_id, s.index, s.count) == ("packer-test", 3, 8)
    name, values = s.fields[0]
    assert np.shares_memory(values, np.frombuffer(msgs[3].fields[0].data, dtype=np.float32))
    assert np.array_equal(values.reshape(s.grid.n_lat, s.grid.n_lon), ds[name].values[3],
                          equal_nan=True)
    t = ds.time.values[3].astype("datetime64[ns]").astype(np.int64) / 1e9
    assert s.valid_time_s == t
    _, packed_msgs = _cycle("packed16")
    p = _fields("packed16")[3]
    name, codes = p.fields[0]
    f = packed_msgs[3].fields[0]
    assert isinstance(codes, PackedField) and not p.problems
    assert np.shares_memory(codes.codes, np.frombuffer(f.packed, dtype=np.uint16))
    assert (codes.add_offset, codes.scale_factor) == (f.add_offset, f.scale_factor)
    ref = ds[name].values[3].reshape(-1)
    assert np.nanmax(np.abs(unpack_field(codes) - ref)) <= f.scale_factor  # packing bound


@pytest.mark.parametrize("encoding", ["float32", "packed16"])
def test_packed_in_any_order_equals_the_sampler_of_the_dataset(encoding):
    """Either encoding: the same bits as a sampler built from the values the messages decode
    to (the dataset itself for float32)."""
    from shiproute_weather.contract.record import without_record
    from shiproute_weather.ros.convert import msgs_to_dataset
    from shiproute_weather.sampling.sampler import ForecastSampler

    ds, msgs = _cycle(encoding)
    fields = _fields(encoding)
    asm: CycleAssembler[SliceFields] = CycleAssembler(sink=lambda _c, s: CyclePacker(s))
    asm.announce("packer-test", 8)
    results = [asm.add_slice(s.cycle_id, s.index, s.count, s) for s in fields[::-1]]
    assert all(r is None for r in results[:-1])
    sampler = results[-1]
    decoded = msgs_to_dataset(msgs)
    if encoding == "float32":
        assert decoded.identical(without_record(ds))  # provenance is on the announcement
    ref = ForecastSampler(decoded, dtype=np.float16)
    assert sampler.variables == ref.variables and sampler.grid == ref.grid
    assert np.array_equal(sampler.times_s, ref.times_s)
    assert np.array_equal(sampler.kernel_data, ref.kernel_data)  # same bits, NaN included


def test_a_field_with_both_encodings_fails_its_cycle():
    import copy

    from shiproute_planner.ros.convert import slice_fields

    msg = copy.deepcopy(_cycle()[1][1])
    msg.fields[2].data = [1.0] * len(msg.fields[2].packed)
    bad = slice_fields(msg)  # never raises (it runs in the subscription callback)
    assert len(bad.problems) == 1 and msg.fields[2].name in bad.problems[0]
    packer = CyclePacker(_fields()[0])
    with pytest.raises(ForecastCycleError, match=f"slice 1: field {msg.fields[2].name}: both"):
        packer.add(1, bad)


def test_slices_older_than_the_ship_are_not_kept():
    fields = _fields()
    times = np.array([s.valid_time_s for s in fields])  # 3-hourly
    ship_s = times[6] + 600.0  # 10 min after slice 6: 12 h back is 10 min after slice 2
    packer = CyclePacker(fields[0], keep_from_s=lambda: ship_s)
    for s in fields:
        packer.add(s.index, s)
    sampler = packer.result()
    first = int(np.argmax(times >= ship_s - KEEP_BEHIND_S))
    assert first == 3 and times[first] <= ship_s  # the slices around the ship stay
    assert np.array_equal(sampler.times_s, times[first:])
    # the dropped slices' pages were never written: they cost no memory
    assert sampler.nbytes == (8 - first) * fields[0].grid.n_lat * fields[0].grid.n_lon * 16 * 2


def test_an_inconsistent_slice_fails_its_cycle_and_later_slices_are_ignored():
    import dataclasses

    from shiproute_weather.contract.canonical import Grid

    fields = _fields()
    asm: CycleAssembler[SliceFields] = CycleAssembler(sink=lambda _c, s: CyclePacker(s))
    asm.announce("packer-test", 8)
    asm.add_slice("packer-test", 0, 8, fields[0])
    g = fields[1].grid
    moved = dataclasses.replace(fields[1], grid=Grid(g.lat0_deg + 1.0, g.dlat_deg, g.n_lat,
                                                     g.lon0_deg, g.dlon_deg, g.n_lon))
    with pytest.raises(ForecastCycleError, match="grid"):
        asm.add_slice("packer-test", 1, 8, moved)
    for s in fields[1:]:
        assert asm.add_slice(s.cycle_id, s.index, s.count, s) is None


def test_valid_times_must_ascend_with_the_index():
    import dataclasses

    fields = _fields()
    swapped = list(fields)
    swapped[2] = dataclasses.replace(fields[2], valid_time_s=fields[5].valid_time_s)
    packer = CyclePacker(fields[0])
    for s in swapped:
        packer.add(s.index, s)
    with pytest.raises(ForecastCycleError, match="ascending"):
        packer.result()


def test_hs_field_for_the_plot_is_the_forecast_at_that_time():
    ds, _ = _cycle()
    packer = CyclePacker(_fields()[0])
    for s in _fields():
        packer.add(s.index, s)
    sampler = packer.result()
    hs = hs_field_at(sampler, float(sampler.times_s[4]))
    ref = ds["sea_surface_wave_significant_height"].values[4]
    got = hs["sea_surface_wave_significant_height"].values[0]
    assert got.shape == ref.shape
    # grid nodes sample to the node value (NaN where the wave model has land), half-rounded
    assert np.array_equal(np.isnan(got), np.isnan(ref))
    assert np.nanmax(np.abs(got - ref)) <= 2.0**-11 * np.nanmax(ref)
