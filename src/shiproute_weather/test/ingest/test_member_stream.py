"""An ensemble NetCDF file is streamed member by member and block by block (issue 19 item 2:
the weather node keeps its memory bounded): the streamed cycle equals the whole load slice for
slice, the member/time budget is the same, and the loader's peak allocation does not grow with
the number of members (tracemalloc: numpy's buffers are traced)."""

from __future__ import annotations

import tracemalloc
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from member_fixtures import realization_netcdf
from shiproute_weather.contract import canonical as cv
from shiproute_weather.ingest.cycle_builder import CycleConfig, build_cycle
from shiproute_weather.ingest.cycle_load import load_cycle
from shiproute_weather.ingest.stream import BLOCK_TIMES, load_slices, streamable
from shiproute_weather.wire.slices import SliceData
from weather_fixtures import small_canonical


def _same_slices(a: list[SliceData], b: list[SliceData]) -> None:
    assert len(a) == len(b)
    for x, y in zip(a, b, strict=True):
        assert (x.slice_index, x.slice_count, x.member, x.member_count, x.member_label,
                x.valid_time_ns, x.grid) == (y.slice_index, y.slice_count, y.member,
                                             y.member_count, y.member_label, y.valid_time_ns,
                                             y.grid)
        assert [f.name for f in x.fields] == [f.name for f in y.fields]
        for f, g in zip(x.fields, y.fields, strict=True):
            np.testing.assert_array_equal(f.data, g.data)


def test_streamed_ensemble_equals_the_whole_load(tmp_path: Path) -> None:
    shifts = [0.0, -2.5, 1.5]
    path = str(realization_netcdf(small_canonical(n_time=5), tmp_path / "ens.nc", shifts))
    cfg = CycleConfig()
    assert streamable([path], cfg)
    info, streamed, notes = load_slices(path, cfg)
    ref_info, whole, ref_notes = build_cycle([path], cfg)
    _same_slices(streamed, whole)
    assert (info.member_count, info.member_labels, info.member_kind, info.slice_count) == \
        (3, ("0", "1", "2"), "ensemble", 15)
    assert (ref_info.member_count, ref_info.member_labels, ref_info.slice_count) == \
        (info.member_count, info.member_labels, info.slice_count)
    assert info.first_valid_time_ns == ref_info.first_valid_time_ns
    assert info.last_valid_time_ns == ref_info.last_valid_time_ns
    assert notes == ref_notes
    # member k really is the file's realization k: eastward wind shifted by shifts[k]
    u = {s.member: s.fields[0].data for s in streamed if s.slice_index % 5 == 2}
    assert streamed[0].fields[0].name == cv.WIND_U
    np.testing.assert_allclose(u[1] - u[0], -2.5, atol=1e-5)
    np.testing.assert_allclose(u[2] - u[0], 1.5, atol=1e-5)


@pytest.mark.parametrize(("max_slices", "max_members"), [(6, 0), (4, 2), (40, 1)])
def test_streamed_budget_is_the_whole_loads(tmp_path: Path, max_slices: int,
                                            max_members: int) -> None:
    path = str(realization_netcdf(small_canonical(n_time=5), tmp_path / "ens.nc",
                                  [0.0, 1.0, 2.0]))
    cfg = CycleConfig(max_slices=max_slices, max_members=max_members)
    info, streamed, notes = load_slices(path, cfg)
    ref_info, whole, ref_notes = build_cycle([path], cfg)
    _same_slices(streamed, whole)
    assert info.slice_count == ref_info.slice_count <= max_slices
    assert info.member_count == ref_info.member_count
    assert info.step_s == ref_info.step_s
    assert sorted(notes) == sorted(ref_notes)


def _member_major_file(path: Path, members: int, n_time: int = 32) -> Path:
    """An ensemble stored like the bundled one: (member, time, lat, lon), 16-bit CF packing
    at 0.01, contiguous; wind and Hs on a 0.5 deg grid of 41 x 81 nodes."""
    lat = np.arange(30.0, 50.0 + 1e-9, 0.5)
    lon = np.arange(160.0, 200.0 + 1e-9, 0.5)
    rng = np.random.default_rng(3)
    shape = (members, n_time, lat.size, lon.size)
    data = {cv.WIND_U: rng.normal(5, 6, shape), cv.WIND_V: rng.normal(0, 6, shape),
            cv.WAVE_HS: rng.uniform(0.5, 8, shape)}
    times = np.datetime64("2026-03-03T12:00", "ns") + np.arange(n_time) * np.timedelta64(3, "h")
    ds = xr.Dataset({n: (("member", "time", "latitude", "longitude"), a.astype(np.float32))
                     for n, a in data.items()},
                    coords={"member": np.arange(members), "time": times, "latitude": lat,
                            "longitude": lon},
                    attrs={"forecast_reference_time": "2026-03-03T12:00:00Z",
                           "source": "unit-test ensemble", "cycle_id": "ens-2026030312"})
    enc: dict = {n: {"dtype": "int16", "scale_factor": np.float32(0.01),
                     "add_offset": np.float32(0.0), "_FillValue": -32768, "zlib": False,
                     "contiguous": True} for n in data}
    enc["time"] = {"units": "hours since 2026-03-03 12:00:00", "dtype": "float64"}
    cv.annotate(ds).to_netcdf(path, encoding=enc)
    return path


def _peak_bytes(path: Path, cfg: CycleConfig) -> tuple[int, int]:
    """(peak traced bytes of one node load, slices) with slices encoded to their index only,
    so the peak is the loader's own working memory."""
    tracemalloc.start()
    try:
        _info, out, _notes, how = load_cycle([str(path)], cfg, (), lambda s: s.slice_index)
        _cur, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert how == "streamed"
    return peak, len(out)


def test_loader_peak_is_one_block_whatever_the_member_count(tmp_path: Path) -> None:
    cfg = CycleConfig(max_slices=1000)
    n_time, n_nodes, n_fields = 32, 41 * 81, 3
    block_f32 = BLOCK_TIMES * n_nodes * n_fields * 4  # one member's block as float32
    peaks = {}
    for members in (2, 8):
        path = _member_major_file(tmp_path / f"ens{members}.nc", members, n_time)
        peaks[members], n = _peak_bytes(path, cfg)
        assert n == members * n_time
    whole_f32 = 8 * n_time * n_nodes * n_fields * 4  # the 8-member ensemble as float32
    # a block exists as read (16-bit), decoded, canonical and as slices at once: a few
    # blocks' worth, never the ensemble; and four times the members cost no more memory
    assert peaks[8] < 6 * block_f32, (peaks, block_f32)
    assert peaks[8] < whole_f32 / 3, (peaks, whole_f32)
    assert peaks[8] < 1.25 * peaks[2], peaks
