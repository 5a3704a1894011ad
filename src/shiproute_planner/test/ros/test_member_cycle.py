"""The planner node's intake of ensemble cycles (ROS-free parts): a cycle of several members is
complete only when every member's slices are in, becomes a canonical dataset with its member
dimension, and a slice that disagrees on the members fails its cycle with the reason."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest
from shiproute_planner.errors import ForecastCycleError
from shiproute_planner.ros.cycle_assembler import CycleAssembler
from shiproute_planner.ros.member_packer import EnsembleCycle, MemberCyclePacker
from shiproute_planner.ros.plan_call import plan_forecast

sys.path.insert(0, str(Path(__file__).resolve().parents[3] / "shiproute_weather/test"))
from member_fixtures import perturbed_members
from weather_fixtures import small_canonical


def _messages(n_members: int = 2, n_time: int = 3):
    from shiproute_weather.ros.convert import dataset_to_msgs

    ds = perturbed_members(small_canonical(n_time=n_time), n_members)
    return ds, dataset_to_msgs(ds)


def _fields(msgs):
    from shiproute_planner.ros.convert import slice_fields

    return [slice_fields(m) for m in msgs]


def _assembler() -> CycleAssembler:
    def sink(_key, first):
        return MemberCyclePacker(first)

    return CycleAssembler(sink=sink)


def test_ensemble_is_complete_only_with_every_member_and_keeps_them() -> None:
    ds, (cycle, msgs) = _messages()
    assert cycle.member_count == 2 and list(cycle.member_labels) == ["0", "1"]
    assert cycle.slice_count == 6 and cycle.member_kind == "ensemble"
    items = _fields(msgs)
    asm = _assembler()
    assert asm.announce("c", cycle.slice_count) is None
    order = [5, 0, 3, 1, 4]  # member 1's first valid time (index 3) in, index 2 still out
    for k in order:
        assert asm.add_slice("c", k, 6, items[k]) is None
    assert asm.missing("c") == 1
    done = asm.add_slice("c", 2, 6, items[2])
    assert isinstance(done, EnsembleCycle) and done.member_count == 2
    got = plan_forecast(done)  # what plan_voyage is handed: the dataset with its members
    assert got.sizes["member"] == 2 and tuple(got["member_label"].values) == ("0", "1")
    for name in ds.data_vars:
        a, b = got[name].values, ds[name].values
        assert np.array_equal(np.isnan(a), np.isnan(b))
        ok = ~np.isnan(b)
        span = float(np.nanmax(b) - np.nanmin(b))
        assert np.all(np.abs(a[ok] - b[ok]) <= span / 65534 + 1e-4 * np.abs(b[ok]) + 1e-6), name
    np.testing.assert_array_equal(got["time"].values, ds["time"].values)


def test_member_count_mismatch_fails_the_cycle_with_the_reason() -> None:
    import dataclasses

    _, (_, msgs) = _messages()
    items = _fields(msgs)

    asm = _assembler()
    asm.announce("c", 6)
    asm.add_slice("c", 0, 6, items[0])
    bad = dataclasses.replace(items[4], member_count=3)
    with pytest.raises(ForecastCycleError, match=r"slice 4: member_count 3 differs from 2.*"
                                                 r"member count mismatch"):
        asm.add_slice("c", 4, 6, bad)
    assert asm.add_slice("c", 1, 6, items[1]) is None  # the failed cycle is closed
    asm = _assembler()
    wrong = dataclasses.replace(items[4], member=0)
    with pytest.raises(ForecastCycleError, match=r"slice 4: member 0, expected 1"):
        asm.add_slice("c", 4, 6, wrong)


def test_a_deterministic_cycle_refuses_a_member_slice() -> None:
    import dataclasses

    from shiproute_planner.ros.cycle_packer import CyclePacker

    _, (_, msgs) = _messages()
    items = _fields(msgs)
    first = dataclasses.replace(items[0], member_count=1, count=6)
    packer = CyclePacker(first)
    with pytest.raises(ForecastCycleError, match=r"member 1 of 2 .*member count mismatch"):
        packer.add(4, dataclasses.replace(items[4]))


def test_intake_counts_an_incomplete_ensemble_with_the_missing_member() -> None:
    """Member 1's slices never arrive; a newer complete cycle supersedes it: the incomplete
    one is never taken, and the drop is counted with the members it lacked."""
    from shiproute_planner.ros.drop_log import DropLog
    from shiproute_planner.ros.forecast_intake import ForecastIntake

    taken: list[tuple] = []
    drops = DropLog(("forecast_cycles", "forecast_slices"))

    class Log:
        def info(self, text: str) -> None:
            taken.append(("log", text))

    intake = ForecastIntake(drops, Log(), accept_older=lambda: True, ship_time_s=lambda: 0.0,
                            in_force=lambda: ("", 0.0),
                            take=lambda s, c, r: taken.append((s, c, r)),
                            report=lambda text: None)
    _, (cycle, msgs) = _messages()
    cycle.cycle_id = "partial"
    intake.on_cycle(cycle)
    for m in msgs[:3]:  # member 0 only
        m.cycle_id = "partial"
        intake.on_slice(m)
    assert not [t for t in taken if t[0] != "log"]
    _, (cycle2, msgs2) = _messages()
    intake.on_cycle(cycle2)
    for m in msgs2:
        intake.on_slice(m)
    done = [t for t in taken if t[0] != "log"]
    assert len(done) == 1 and done[0][1] == "test-2026030312"
    assert isinstance(done[0][0], EnsembleCycle)
    assert done[0][0].dataset.attrs["member_kind"] == "ensemble"
    assert drops.count("forecast_cycles") == 1 and drops.count("forecast_slices") == 3
    assert "members [1] of 2 lack slices" in drops.last("forecast_cycles")
    assert any("2 member(s)" in t[1] for t in taken if t[0] == "log")
