"""Replay timing with a fake wall clock: rate scaling, gaps, out-of-order, pause, seek."""

from __future__ import annotations

import itertools

import pytest
from shiproute_ais_replay.replay.scheduler import ReplayScheduler

S = 1_000_000_000


def _run(sched: ReplayScheduler, bag_times_ns: list[int], start_wall: float = 100.0):
    """Release every message at its due time; returns the wall release times."""
    now, out = start_wall, []
    for t in bag_times_ns:
        now += sched.wait_s(t, now)
        sched.release(t, now)
        out.append(now)
    return out


def test_rate_scales_inter_arrival_times():
    walls = _run(ReplayScheduler(rate=100.0), [0, 1 * S, 2 * S, 12 * S])
    assert [b - a for a, b in itertools.pairwise(walls)] == pytest.approx(
        [0.01, 0.01, 0.1])


def test_long_gap_jumps_ahead_instead_of_sleeping():
    sched = ReplayScheduler(rate=1.0, max_gap_wall_s=5.0)
    day = 86_400 * S
    walls = _run(sched, [0, 1 * S, day, day + 2 * S])
    assert walls[2] - walls[1] == pytest.approx(0.0)  # the day-long gap is skipped
    assert walls[3] - walls[2] == pytest.approx(2.0)  # normal timing resumes after it
    assert sched.counts.gaps_jumped == 1
    assert sched.counts.gap_skipped_s == pytest.approx(86_399.0)


def test_out_of_order_message_goes_at_once_and_clock_never_runs_back():
    sched = ReplayScheduler(rate=10.0)
    now = 0.0
    for t in (0, 5 * S):
        now += sched.wait_s(t, now)
        sched.release(t, now)
    assert sched.wait_s(3 * S, now) == 0.0
    assert sched.release(3 * S, now) == 5 * S
    assert sched.counts.out_of_order == 1
    assert sched.clock_ns == 5 * S


def test_pause_shifts_the_schedule_by_the_paused_time():
    sched = ReplayScheduler(rate=1.0)
    sched.wait_s(0, 10.0)
    sched.release(0, 10.0)
    sched.pause(10.5)
    assert sched.paused
    sched.resume(20.5)  # paused for 10 s
    assert sched.wait_s(1 * S, 20.5) == pytest.approx(0.5)


def test_restart_makes_next_message_due_now_and_lag_is_measured():
    sched = ReplayScheduler(rate=2.0)
    sched.wait_s(0, 0.0)
    sched.release(0, 0.0)
    assert sched.wait_s(4 * S, 0.0) == pytest.approx(2.0)
    sched.release(4 * S, 2.25)  # published 0.25 s late
    assert sched.counts.max_lag_s == pytest.approx(0.25)
    sched.restart()
    assert sched.wait_s(100 * S, 50.0) == 0.0


def test_unthrottled_rate_never_waits():
    sched = ReplayScheduler(rate=0.0)
    assert _run(sched, [0, S, 10 * S]) == [100.0, 100.0, 100.0]
