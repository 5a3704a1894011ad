"""Ensembles between real nodes (issue 19, items 1-2): the weather node publishes every member of
a 2-member file; the planner node assembles the complete 2-member cycle; a cycle whose member 1
never arrives is not completed and is counted with the member it lacks."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src/shiproute_weather/test"))

pytestmark = pytest.mark.ros

rclpy = pytest.importorskip("rclpy")
pytest.importorskip("shiproute_msgs.msg")

import numpy as np  # noqa: E402
from diagnostic_msgs.msg import DiagnosticArray  # noqa: E402
from member_fixtures import perturbed_members, realization_netcdf  # noqa: E402
from rclpy.executors import SingleThreadedExecutor  # noqa: E402
from rosproc import RosProcess, random_domain_id, ros_context, spin_until  # noqa: E402
from shiproute_core.topics import FORECAST_CYCLE, FORECAST_SLICES  # noqa: E402
from shiproute_weather.contract import canonical as cv  # noqa: E402
from shiproute_weather.ros.convert import dataset_to_msgs, msgs_to_dataset  # noqa: E402
from shiproute_weather.ros.node import latched  # noqa: E402
from weather_fixtures import small_canonical  # noqa: E402

from shiproute_msgs.msg import ForecastCycle, ForecastSlice  # noqa: E402


class Peer:
    """Subscriber of the forecast topics and /diagnostics; publisher of hand-made cycles."""

    def __init__(self, context: Any) -> None:
        self.node = rclpy.create_node("ensemble_test_peer", context=context)
        self.cycles: list[ForecastCycle] = []
        self.slices: list[ForecastSlice] = []
        self.diag: dict[str, dict[str, str]] = {}
        self.node.create_subscription(ForecastCycle, FORECAST_CYCLE, self.cycles.append,
                                      latched(1))
        self.node.create_subscription(ForecastSlice, FORECAST_SLICES, self.slices.append,
                                      latched(50))
        self.node.create_subscription(DiagnosticArray, "/diagnostics", self._diag, 10)
        self.cycle_pub = self.node.create_publisher(ForecastCycle, FORECAST_CYCLE, latched(1))
        self.slice_pub = self.node.create_publisher(ForecastSlice, FORECAST_SLICES, latched(50))
        self.executor = SingleThreadedExecutor(context=context)
        self.executor.add_node(self.node)

    def _diag(self, msg: DiagnosticArray) -> None:
        for s in msg.status:
            self.diag[s.name] = {kv.key: kv.value for kv in s.values}

    def publish(self, cycle: ForecastCycle, slices: list[ForecastSlice]) -> None:
        self.cycle_pub.publish(cycle)
        for m in slices:
            self.slice_pub.publish(m)

    def close(self) -> None:
        self.executor.shutdown()
        self.node.destroy_node()


def _cycle(cycle_id: str, ref: str, seed: int) -> tuple[ForecastCycle, list[ForecastSlice]]:
    ds = perturbed_members(small_canonical(n_time=3, ref=ref, cycle_id=cycle_id), 2, seed=seed)
    return dataset_to_msgs(ds)


def test_two_member_cycle_from_weather_node_to_planner_intake(tmp_path: Path) -> None:
    base = small_canonical(n_time=3)
    src = realization_netcdf(base, tmp_path / "ens.nc", [0.0, 3.0])
    dom = random_domain_id()
    env = {"SHIPROUTE_DATA_DIR": str(tmp_path / "cache")}
    with RosProcess.script("shiproute_weather_node", "--ros-args", "-p",
                           f"forecast_files:=['{src}']", "-p", "max_slices:=50",
                           domain_id=dom, env=env, name="weather") as weather, \
            RosProcess.script("shiproute_planner_node", "--ros-args", "-p", "origin:=Busan",
                              "-p", "destination:=Long Beach",
                              "-p", "rta:=2026-03-16T18:00:00Z", "-p", "budget_s:=0.5",
                              "-p", "write_png:=false", domain_id=dom, env=env,
                              name="planner") as planner, ros_context(dom) as ctx:
        peer = Peer(ctx)
        try:
            weather.wait_for_line(r"published cycle \S+: 6 slices of 2 member", timeout_s=90)
            spin_until(peer.executor, lambda: len(peer.cycles) > 0, 30, "cycle announcement")
            cycle_id = peer.cycles[-1].cycle_id
            spin_until(peer.executor, lambda: len(
                {m.slice_index for m in peer.slices if m.cycle_id == cycle_id}) == 6, 30,
                f"six slices of {cycle_id} (have "
                f"{sorted({(m.cycle_id, m.slice_index) for m in peer.slices})})")
            cycle = peer.cycles[-1]
            assert cycle.member_count == 2 and list(cycle.member_labels) == ["0", "1"]
            assert cycle.member_kind == "ensemble" and cycle.slice_count == 6
            msgs = sorted({m.slice_index: m for m in peer.slices
                           if m.cycle_id == cycle_id}.values(), key=lambda m: m.slice_index)
            assert [(m.member, m.member_count, m.member_label) for m in msgs[2:4]] == [
                (0, 2, "0"), (1, 2, "1")]
            got = msgs_to_dataset(msgs, cycle.member_kind)
            du = got[cv.WIND_U].values[1] - got[cv.WIND_U].values[0]
            step = max(f.scale_factor for m in msgs for f in m.fields if f.name == cv.WIND_U)
            assert np.all(np.abs(du - 3.0) <= step + 1e-5)  # the two members' winds as written
            planner.wait_for_line(rf"forecast cycle {cycle_id} complete: 2 member\(s\)",
                                  timeout_s=120)
            # member 1 of the next cycle never arrives; a newer complete cycle supersedes it
            partial, partial_slices = _cycle("partial-2026030318", "2026-03-03T18:00:00", 3)
            peer.publish(partial, partial_slices[:3])
            done, done_slices = _cycle("complete-2026030400", "2026-03-04T00:00:00", 4)
            peer.publish(done, done_slices)
            planner.wait_for_line(r"forecast cycle complete-2026030400 complete: 2 member",
                                  timeout_s=60)

            def counted() -> dict[str, str] | None:
                d = peer.diag.get("shiproute_planner", {})
                reason = d.get("forecast_cycles_last_reason", "")
                in_force = d.get("forecast_cycle_in_force", "")
                # the newer complete cycle comes into force once the planner takes it up
                return d if ("partial-2026030318" in reason
                             and in_force == "complete-2026030400") else None

            d = spin_until(peer.executor, counted, 90,
                           "incomplete cycle counted, the newer complete one in force")
            assert int(d["forecast_cycles_dropped"]) >= 1
            assert "members [1] of 2 lack slices" in d["forecast_cycles_last_reason"]
            assert int(d["forecast_slices_dropped"]) >= 3
            assert d["forecast_cycle_in_force"] == "complete-2026030400"
            assert weather.running and planner.running
        finally:
            peer.close()
