"""The search clock's allowance for coastline tiles built during a search: the seconds the
tile set says it spent building, capped, and the plan's statement of how many it built."""

from __future__ import annotations

import numpy as np
import pytest
from shiproute_planner.tile_allowance import TileAllowance

SCILLY = (-6.32, 49.93)  # a coast: a tile here holds land and sea


def test_allowance_counts_the_tiles_built_since_it_started_and_caps_the_seconds(empty_tiles):
    # one tile built before the search started is not the search's
    empty_tiles.distance_nm(np.array([SCILLY[0]]), np.array([SCILLY[1]]))
    wide = TileAllowance(cap_s=1e6)
    tight = TileAllowance(cap_s=1e-6)
    assert wide.spent() == (0, 0.0) and wide.statement() == ()
    # two tiles east of it (0.5 deg each), built during the search
    empty_tiles.distance_nm(np.array([SCILLY[0] + 0.5, SCILLY[0] + 1.0]),
                            np.array([SCILLY[1], SCILLY[1]]))
    tiles, seconds = wide.spent()
    assert tiles == 2 and seconds > 0.0
    assert wide.excused_s() == pytest.approx(seconds)
    assert tight.excused_s() == 1e-6  # never more than the cap
    (said,) = tight.statement()
    assert said.startswith("search: built 2 full-resolution coastline tile(s)")
    assert "extended by 0.00 s" in said


def test_snapshot_holds_the_same_tiles_and_builds_its_own(empty_tiles):
    lon, lat = np.array([SCILLY[0]]), np.array([SCILLY[1]])
    before = empty_tiles.distance_nm(lon, lat)
    copy = empty_tiles.snapshot()
    assert copy.count == empty_tiles.count == 1 and copy.path is None
    assert np.array_equal(copy.distance_nm(lon, lat), before)
    assert copy.built == 0  # read, not rebuilt
    copy.distance_nm(lon + 0.5, lat)
    assert copy.count == 2 and empty_tiles.count == 1



def test_plan_clock_gives_the_spans_still_to_run_the_time_tiles_took(monkeypatch):
    from shiproute_planner import plan_timing

    now, built_s = [100.0], [7.0]  # 7 s of builds before the plan: not its own
    monkeypatch.setattr(plan_timing.time, "perf_counter", lambda: now[0])
    monkeypatch.setattr(plan_timing, "tile_builds", lambda: (0, built_s[0]))
    clock = plan_timing.PlanClock()
    reserve = plan_timing.checks_reserve_s(3.0)
    now[0] += 2.0  # 2 s into a 3-s plan, 1.5 s of it building tiles
    built_s[0] += 1.5
    assert clock.left_s(3.0) == pytest.approx(3.0 - 2.0 + 1.5 - reserve)
    built_s[0] += 10.0  # never more than the budget excused
    assert clock.left_s(3.0) == pytest.approx(3.0 - 2.0 + 3.0 - reserve)
