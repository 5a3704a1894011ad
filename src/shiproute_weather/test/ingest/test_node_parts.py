"""ROS-free parts of the node: watcher debounce, cycle building, streaming, import hygiene."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from shiproute_weather.errors import WeatherError
from shiproute_weather.ingest.combine import Box
from shiproute_weather.ingest.cycle_builder import CycleConfig, build_cycle, corridor_box
from shiproute_weather.ingest.stream import load_slices, streamable
from shiproute_weather.ingest.watch import DirectoryWatcher
from shiproute_weather.wire.slices import slices_to_dataset
from weather_fixtures import small_canonical, write_nc


def test_library_does_not_import_rclpy() -> None:
    code = ("import sys, shiproute_weather.ingest.loaders, shiproute_weather.sampling.sampler, "
            "shiproute_weather.scenarios, shiproute_weather.ingest.stream, shiproute_weather.cli; "
            "print('rclpy' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_watcher_waits_until_size_is_stable(tmp_path: Path) -> None:
    w = DirectoryWatcher(tmp_path, settle_s=1.0)
    f = tmp_path / "a.grib2"
    f.write_bytes(b"x" * 10)
    (tmp_path / "b.nc.part").write_bytes(b"y")
    assert w.poll(0.0) == []
    f.write_bytes(b"x" * 20)  # still growing
    assert w.poll(0.8) == []
    assert w.poll(1.5) == []  # unchanged for only 0.7 s
    assert w.poll(2.0) == [f]
    assert w.poll(5.0) == []  # reported once


def test_corridor_box_across_the_antimeridian() -> None:
    box = corridor_box([35.1, 48.0, 33.7], [129.1, 180.0, -118.25], 5.0)
    got = np.array([box.lat_min_deg, box.lat_max_deg, box.lon_min_deg, box.lon_max_deg])
    np.testing.assert_allclose(got, [28.7, 53.0, 124.1, 246.75], atol=1e-9)


def test_streaming_equals_full_load(tmp_path: Path) -> None:
    p = str(write_nc(small_canonical(n_time=21), tmp_path / "s.nc"))
    cfg = CycleConfig(box=Box(31.0, 38.0, 172.0, 190.0))
    assert streamable([p], cfg)
    info_full, slices_full, _ = build_cycle([p], cfg)
    info, slices, _ = load_slices(p, cfg)
    assert info == info_full
    assert [s.slice_index for s in slices] == list(range(21))
    xr.testing.assert_identical(slices_to_dataset(slices), slices_to_dataset(slices_full))


def test_bounds_thin_grid_and_cut_slices(tmp_path: Path) -> None:
    p = str(write_nc(small_canonical(n_time=9), tmp_path / "t.nc"))
    cfg = CycleConfig(max_slice_bytes=20_000, max_slices=4, slice_interval_s=6 * 3600.0)
    info, slices, notes = build_cycle([p], cfg)
    assert info.step_s == 6 * 3600.0 and len(slices) == 4 and info.slice_count == 4
    assert all(s.nbytes <= 20_000 for s in slices)
    assert any("thinned" in n for n in notes) and any("first 4" in n for n in notes)


def test_streaming_thins_large_slices(tmp_path: Path) -> None:
    p = str(write_nc(small_canonical(n_time=3), tmp_path / "big.nc"))
    _info, slices, notes = load_slices(p, CycleConfig(max_slice_bytes=20_000))
    assert all(s.nbytes <= 20_000 for s in slices) and "thinned" in notes[0]
    assert slices[0].grid.dlat_deg == 1.0  # every second row of the 0.5 deg grid


def test_streaming_rejects_a_bad_file_before_yielding(tmp_path: Path) -> None:
    ds = small_canonical(n_time=40)
    # a block late in the file whose wave heights are all impossible (an undeclared fill)
    ds["sea_surface_wave_significant_height"][32:] = np.float32(9999.0)
    p = str(write_nc(ds, tmp_path / "late_error.nc"))
    with pytest.raises(WeatherError, match=r"late_error\.nc"):
        load_slices(p, CycleConfig())
