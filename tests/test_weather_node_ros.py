"""Cross-process tests of the weather node: late joiners, watched directory, corrupt files,
slice encoding (16-bit packed by default, float32 on request; bad values rejected)."""

from __future__ import annotations

import os
import shutil
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src/shiproute_weather/test"))

pytestmark = pytest.mark.ros

rclpy = pytest.importorskip("rclpy")
pytest.importorskip("shiproute_msgs.msg")

import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus  # noqa: E402
from rclpy.executors import SingleThreadedExecutor  # noqa: E402
from rosproc import RosProcess, random_domain_id, ros_context, spin_until  # noqa: E402
from shiproute_core.topics import FORECAST_CYCLE, FORECAST_LOAD, FORECAST_SLICES  # noqa: E402
from shiproute_weather.contract.record import without_record  # noqa: E402
from shiproute_weather.ingest.loaders import open_forecast  # noqa: E402
from shiproute_weather.ros.convert import msgs_to_dataset  # noqa: E402
from shiproute_weather.ros.node import latched  # noqa: E402
from weather_fixtures import small_canonical, write_nc  # noqa: E402

from shiproute_msgs.msg import ForecastCycle, ForecastSlice  # noqa: E402
from shiproute_msgs.srv import LoadForecast  # noqa: E402


class Listener:
    """Test-side subscriber collecting cycles, slices and weather diagnostics."""

    def __init__(self, context: object, max_slices: int = 50) -> None:
        self.node = rclpy.create_node("weather_test_listener", context=context)
        self.cycles: list[ForecastCycle] = []
        self.slices: list[ForecastSlice] = []
        self.diags: list[DiagnosticStatus] = []
        self.node.create_subscription(ForecastCycle, FORECAST_CYCLE, self.cycles.append, latched(1))
        self.node.create_subscription(ForecastSlice, FORECAST_SLICES, self.slices.append,
                                      latched(max_slices))
        self.node.create_subscription(DiagnosticArray, "/diagnostics", self._diag, 10)
        self.executor = SingleThreadedExecutor(context=context)
        self.executor.add_node(self.node)

    def _diag(self, msg: DiagnosticArray) -> None:
        self.diags.extend(s for s in msg.status if s.name.startswith("shiproute_weather"))

    def cycle_slices(self, cycle_id: str) -> list[ForecastSlice]:
        got = {m.slice_index: m for m in self.slices if m.cycle_id == cycle_id}
        return [got[k] for k in sorted(got)]

    def wait_cycle(self, cycle_id: str, n: int, timeout_s: float = 30.0) -> list[ForecastSlice]:
        spin_until(self.executor, lambda: any(c.cycle_id == cycle_id for c in self.cycles)
                   and len(self.cycle_slices(cycle_id)) == n, timeout_s, f"cycle {cycle_id}")
        return self.cycle_slices(cycle_id)

    def close(self) -> None:
        self.executor.shutdown()
        self.node.destroy_node()


def _node(tmp: Path, dom: int, *params: str) -> RosProcess:
    env = {"SHIPROUTE_DATA_DIR": str(tmp / "cache")}
    args = ["--ros-args", "-p", f"watch_dir:={tmp / 'watch'}", "-p", "settle_s:=0.3",
            "-p", "watch_period_s:=0.2", "-p", "max_slices:=50"]
    for p in params:
        args += ["-p", p]
    return RosProcess.script("shiproute_weather_node", *args, domain_id=dom, env=env,
                             name="weather")


def test_late_joiner_gets_whole_cycle(tmp_path: Path) -> None:
    (tmp_path / "watch").mkdir()
    src = write_nc(small_canonical(n_time=7), tmp_path / "first.nc")
    expected = without_record(open_forecast([src]))  # provenance travels on the announcement
    dom = random_domain_id()
    with _node(tmp_path, dom, f"forecast_files:=['{src}']") as proc:
        proc.wait_for_line(r"published cycle test-2026030312", timeout_s=60)
        with ros_context(dom) as ctx:  # joins after the cycle was published
            lis = Listener(ctx)
            try:
                msgs = lis.wait_cycle("test-2026030312", 7)
                assert lis.cycles[-1].slice_count == 7
                assert lis.cycles[-1].source_files == [str(src)]
                _assert_packed_equivalent(msgs, expected)
            finally:
                lis.close()


def _assert_packed_equivalent(msgs: list[ForecastSlice], expected: xr.Dataset) -> None:
    """Default encoding: every field packed, the decoded cycle equal to `expected` in grid,
    times, attrs and NaN pattern, values within each field's scale_factor / 2 (+ float32)."""
    got = msgs_to_dataset(msgs)
    assert got.attrs == expected.attrs
    xr.testing.assert_identical(got.coords.to_dataset(), expected.coords.to_dataset())
    for m in msgs:
        for f in m.fields:
            assert len(f.data) == 0 and len(f.packed) == m.n_lat * m.n_lon
            a = got[f.name].values[m.slice_index].astype(np.float64)
            b = expected[f.name].values[m.slice_index].astype(np.float64)
            assert np.array_equal(np.isnan(a), np.isnan(b))
            ok = ~np.isnan(b)
            assert np.all(np.abs(a[ok] - b[ok]) <= f.scale_factor / 2 * (1 + 1e-9)
                          + np.spacing(np.abs(b[ok]).astype(np.float32))), f.name


def _set_encoding(lis: Listener, value: str) -> tuple[bool, str]:
    from rcl_interfaces.srv import SetParameters
    from rclpy.parameter import Parameter

    cli = lis.node.create_client(SetParameters, "/shiproute_weather/set_parameters")
    assert cli.wait_for_service(timeout_sec=10)
    req = SetParameters.Request(parameters=[Parameter("slice_encoding",
                                                      value=value).to_parameter_msg()])
    fut = cli.call_async(req)
    spin_until(lis.executor, fut.done, 15, "set_parameters reply")
    res = fut.result().results[0]
    return res.successful, res.reason


def test_slice_encoding_parameter(tmp_path: Path) -> None:
    """A bad launch value is rejected (default used); at run time float32 is accepted and the
    next cycle is exact, a bad value is refused with the reason and the node keeps going."""
    (tmp_path / "watch").mkdir()
    src = write_nc(small_canonical(n_time=3), tmp_path / "first.nc")
    expected = without_record(open_forecast([src]))  # provenance travels on the announcement
    dom = random_domain_id()
    with _node(tmp_path, dom, f"forecast_files:=['{src}']", "slice_encoding:=float16") as proc, \
            ros_context(dom) as ctx:
        proc.wait_for_line(r"rejected parameter: slice_encoding must be one of packed16, "
                           r"float32, got 'float16'; using packed16", timeout_s=60)
        lis = Listener(ctx)
        try:
            _assert_packed_equivalent(lis.wait_cycle("test-2026030312", 3, timeout_s=60),
                                      expected)
            spin_until(lis.executor, lambda: any(
                {kv.key: kv.value for kv in d.values}.get("slice_encoding") == "packed16"
                for d in lis.diags), 15, "diagnostics naming the encoding")
            ok, reason = _set_encoding(lis, "bogus")
            assert not ok and "slice_encoding must be one of packed16, float32" in reason
            assert _set_encoding(lis, "float32") == (True, "")
            again = small_canonical(n_time=2, seed=3, cycle_id="exact-2026030318")
            path = write_nc(again, tmp_path / "exact.nc")
            cli = lis.node.create_client(LoadForecast, FORECAST_LOAD)
            assert cli.wait_for_service(timeout_sec=10)
            fut = cli.call_async(LoadForecast.Request(paths=[str(path)]))
            spin_until(lis.executor, fut.done, 60, "load reply")
            assert fut.result().accepted, fut.result().message
            msgs = lis.wait_cycle("exact-2026030318", 2)
            assert all(len(f.packed) == 0 for m in msgs for f in m.fields)
            exact = without_record(open_forecast([path]))
            xr.testing.assert_identical(msgs_to_dataset(msgs), exact)
            spin_until(lis.executor, lambda: any(
                {kv.key: kv.value for kv in d.values}.get("bytes_per_slice")
                == str(13 * 21 * 51 * 4) for d in lis.diags), 15, "float32 bytes in diagnostics")
            assert proc.running
        finally:
            lis.close()


def test_new_file_and_corrupt_file(tmp_path: Path) -> None:
    watch = tmp_path / "watch"
    watch.mkdir()
    write_nc(small_canonical(n_time=4, cycle_id="one-2026030312"), watch / "one.nc")
    dom = random_domain_id()
    with _node(tmp_path, dom) as proc, ros_context(dom) as ctx:
        proc.wait_for_line(r"ready", timeout_s=60)
        lis = Listener(ctx)
        try:
            lis.wait_cycle("one-2026030312", 4, timeout_s=60)
            # a new cycle dropped into the watched directory (written, then renamed)
            two = small_canonical(n_time=6, seed=2, ref="2026-03-03T18:00:00",
                                  cycle_id="two-2026030318")
            write_nc(two, tmp_path / "two.tmp.nc")
            shutil.move(tmp_path / "two.tmp.nc", watch / "two.nc")
            lis.wait_cycle("two-2026030318", 6)
            # a corrupt file: announced as an error, the previous cycle stays in force
            (watch / "broken.nc").write_bytes(b"CDF\x01" + os.urandom(2000))
            spin_until(lis.executor, lambda: any(
                d.level == DiagnosticStatus.ERROR and "broken.nc" in d.message + "".join(
                    kv.value for kv in d.values) for d in lis.diags), 30, "error diagnostic")
            assert lis.cycles[-1].cycle_id == "two-2026030318"
            # the service refuses a truncated GRIB file and names it
            grib = watch.parent / "cut.grib2"
            real = Path("/usr/share/doc/python-grib-doc/examples/gfs.t12z.pgrbf120.2p5deg.grib2")
            grib.write_bytes(real.read_bytes()[:5000] if real.exists() else b"GRIB" + b"\0" * 99)
            cli = lis.node.create_client(LoadForecast, FORECAST_LOAD)
            assert cli.wait_for_service(timeout_sec=10)
            fut = cli.call_async(LoadForecast.Request(paths=[str(grib)]))
            spin_until(lis.executor, fut.done, 30, "service reply")
            assert not fut.result().accepted and "cut.grib2" in fut.result().message
            assert proc.running
        finally:
            lis.close()


def test_several_files_make_one_cycle_with_its_record(tmp_path: Path) -> None:
    """Wind from one file and currents from another (own grid and time step) via the load
    service and via the watched directory: one cycle whose announcement names each field's
    file and the load's notes (waves estimated from wind), also on /diagnostics."""
    from shiproute_weather.contract import canonical as cv

    (tmp_path / "watch").mkdir()
    wind = small_canonical(n_time=5, cycle_id="wind-2026030312")[[cv.WIND_U, cv.WIND_V]]
    cur = small_canonical(n_time=3, lat=(28.0, 42.0, 1.0), lon=(165.0, 200.0, 1.0), seed=3)
    cur = cur[[cv.CURRENT_U, cv.CURRENT_V]].isel(time=[0, 2])  # 6-hourly
    a = write_nc(wind, tmp_path / "gfs_wind.nc")
    b = write_nc(cur, tmp_path / "cmems_cur.nc")
    dom = random_domain_id()
    with _node(tmp_path, dom) as proc, ros_context(dom) as ctx:
        proc.wait_for_line(r"ready", timeout_s=60)
        lis = Listener(ctx)
        try:
            cli = lis.node.create_client(LoadForecast, FORECAST_LOAD)
            assert cli.wait_for_service(timeout_sec=10)
            fut = cli.call_async(LoadForecast.Request(paths=[str(a), str(b)]))
            spin_until(lis.executor, fut.done, 60, "service reply")
            assert fut.result().accepted, fut.result().message
            lis.wait_cycle("wind-2026030312", 5)
            cycle = lis.cycles[-1]
            sources = dict(zip(cycle.fields, cycle.field_sources, strict=True))
            assert sources[cv.WIND_U] == str(a) and sources[cv.CURRENT_V] == str(b)
            assert sources[cv.WAVE_HS] == str(a)  # grown from that file's wind
            assert any(n.startswith("waves estimated from wind") for n in cycle.notes)
            spin_until(lis.executor, lambda: any(
                "waves estimated from wind" in "".join(kv.value for kv in d.values)
                for d in lis.diags), 30, "diagnostics with the load notes")
            # the same two files dropped together into the watched directory: one cycle
            shutil.copy(a, tmp_path / "watch" / "gfs_wind.nc")
            shutil.copy(b, tmp_path / "watch" / "cmems_cur.nc")
            n_before = len(lis.cycles)
            spin_until(lis.executor, lambda: len(lis.cycles) > n_before, 60, "watched cycle")
            got = lis.cycles[-1]
            assert {cv.WIND_U, cv.CURRENT_U, cv.WAVE_HS} <= set(got.fields)
            assert len(got.source_files) == 2
            assert proc.running
        finally:
            lis.close()
