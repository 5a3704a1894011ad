"""LoadForecast with multi-model members against a running weather node (issue 19 item 2):
`member_files` / `member_labels` load a multi-model cycle as the start-up parameters do; a bad
request is refused with its reason and the last good cycle stays in force; an ensemble file is
streamed and the diagnostics state what the cycle costs on the wire and what bounds it."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src/shiproute_weather/test"))

pytestmark = pytest.mark.ros

rclpy = pytest.importorskip("rclpy")
pytest.importorskip("shiproute_msgs.msg")

from diagnostic_msgs.msg import DiagnosticArray  # noqa: E402
from member_fixtures import realization_netcdf  # noqa: E402
from rclpy.executors import SingleThreadedExecutor  # noqa: E402
from rosproc import RosProcess, random_domain_id, ros_context, spin_until  # noqa: E402
from shiproute_core.topics import DIAGNOSTICS, FORECAST_CYCLE, FORECAST_LOAD  # noqa: E402
from shiproute_weather.ros.node import DIAG_NAME, latched  # noqa: E402
from weather_fixtures import small_canonical, write_nc  # noqa: E402

from shiproute_msgs.msg import ForecastCycle  # noqa: E402
from shiproute_msgs.srv import LoadForecast  # noqa: E402


class Client:
    """LoadForecast caller, cycle and diagnostics listener."""

    def __init__(self, context: Any) -> None:
        self.node = rclpy.create_node("members_test_client", context=context)
        self.cycles: list[ForecastCycle] = []
        self.diag: dict[str, str] = {}
        self.node.create_subscription(ForecastCycle, FORECAST_CYCLE, self.cycles.append,
                                      latched(1))
        self.node.create_subscription(DiagnosticArray, DIAGNOSTICS, self._diag, 10)
        self.cli = self.node.create_client(LoadForecast, FORECAST_LOAD)
        self.executor = SingleThreadedExecutor(context=context)
        self.executor.add_node(self.node)

    def _diag(self, msg: DiagnosticArray) -> None:
        for s in msg.status:
            if s.name == DIAG_NAME:
                self.diag = {kv.key: kv.value for kv in s.values}

    def load(self, **fields: list[str]) -> LoadForecast.Response:
        assert self.cli.wait_for_service(timeout_sec=10)
        fut = self.cli.call_async(LoadForecast.Request(**fields))
        spin_until(self.executor, fut.done, 90, "LoadForecast reply")
        return fut.result()

    def close(self) -> None:
        self.executor.shutdown()
        self.node.destroy_node()


def test_load_forecast_members_and_refusals(tmp_path: Path) -> None:
    gfs = small_canonical(n_time=5)
    ecmwf = small_canonical(n_time=3, lat=(28.0, 42.0, 1.0), lon=(165.0, 200.0, 1.0), seed=5)
    a = write_nc(gfs, tmp_path / "gfs.nc")
    b = write_nc(ecmwf.isel(time=[0, 2]), tmp_path / "ecmwf.nc")
    far = write_nc(small_canonical(n_time=3, lat=(-40.0, -30.0, 0.5), lon=(10.0, 30.0, 0.5)),
                   tmp_path / "south_atlantic.nc")
    ens = realization_netcdf(small_canonical(n_time=4), tmp_path / "ens.nc", [0.0, 2.0, -1.0])
    dom = random_domain_id()
    env = {"SHIPROUTE_DATA_DIR": str(tmp_path / "cache")}
    with RosProcess.script("shiproute_weather_node", "--ros-args", "-p", "max_slices:=50",
                           domain_id=dom, env=env, name="weather") as weather, \
            ros_context(dom) as ctx:
        c = Client(ctx)
        try:
            res = c.load(member_files=[str(a), str(b)], member_labels=["gfs", "ecmwf"])
            assert res.accepted, res.message
            spin_until(c.executor, lambda: c.cycles and c.cycles[-1].cycle_id == res.cycle_id,
                       30, "the multi-model cycle")
            cyc = c.cycles[-1]
            assert (cyc.member_count, list(cyc.member_labels), cyc.member_kind,
                    cyc.slice_count) == (2, ["gfs", "ecmwf"], "multi-model", 10)
            good = res.cycle_id
            refusals = [
                ({"member_files": [str(a), str(b)], "member_labels": ["gfs"]},
                 "1 member labels for 2 members"),
                ({"member_files": [str(a), str(far)]}, "south_atlantic.nc"),
                ({"member_files": [str(a), str(tmp_path / "missing.nc")]},
                 "missing.nc: file does not exist"),
                ({"paths": [str(a)], "member_files": [str(b)]}, "not both"),
                ({"member_labels": ["x"]}, "member_labels given without member_files"),
                ({"member_files": [str(a), str(b)], "member_labels": ["gfs", "gfs"]},
                 "gfs"),
            ]
            for k, (fields, reason) in enumerate(refusals, start=1):
                res = c.load(**fields)
                assert not res.accepted and reason in res.message, (fields, res.message)
                spin_until(c.executor, lambda k=k: int(c.diag.get("loads_refused", 0)) == k,
                           15, f"refusal {k} in the diagnostics")
                assert c.diag["cycle_id"] == good  # the last good cycle stays in force
                assert reason in c.diag["loads_refused_last_reason"]
            assert c.cycles[-1].cycle_id == good
            # an ensemble file: streamed member by member; its wire cost stated
            res = c.load(paths=[str(ens)])
            assert res.accepted, res.message
            spin_until(c.executor, lambda: c.diag.get("cycle_id") == res.cycle_id
                       and c.diag.get("members") == "3", 30, "the ensemble cycle's diagnostics")
            d = c.diag
            assert d["load_path"] == "streamed"
            n_nodes = 21 * 51  # small_canonical's 0.5 deg grid, 30..40 N x 170..195 E
            # 3 fields (u10, v10, swh), 2 B each packed, 3 members x 4 valid times
            assert int(d["cycle_wire_bytes"]) == 12 * 3 * n_nodes * 2
            assert int(d["bytes_per_slice"]) == 3 * n_nodes * 2
            assert "3 member(s) x 4 valid times = 12 slices" in d["wire_budget"]
            assert "packed16" in d["wire_budget"] and "<= 50 slices" in d["wire_budget"]
            assert weather.running
        finally:
            c.close()
