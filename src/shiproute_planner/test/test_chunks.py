"""The planner's chunked thread fan-out (`chunks.in_chunks`): every row done exactly once, in
pieces taken by whichever thread is free, and a failure raised, not lost."""

from __future__ import annotations

import contextlib
import itertools
import threading

import numpy as np
import pytest
from shiproute_planner.threads import set_planner_threads

from shiproute_planner import chunks


@pytest.fixture()
def two_threads():
    before = chunks.planner_threads()
    set_planner_threads(2)
    yield
    set_planner_threads(before)


@pytest.mark.parametrize("per_thread", [1, 4])
@pytest.mark.parametrize("n", [0, 1, 15, 16, 33, 200, 4400, 4401])
def test_pieces_cover_every_row_once_in_order(n, per_thread, two_threads, monkeypatch):
    monkeypatch.setattr(chunks, "CHUNKS_PER_THREAD", per_thread)
    k, pieces = chunks.chunk_bounds(n)
    assert pieces[0][0] == 0 and pieces[-1][1] == n
    assert all(a1 == b0 for (_, a1), (b0, _) in itertools.pairwise(pieces))
    assert len(pieces) <= k * chunks.CHUNKS_PER_THREAD
    if k > 1:  # no piece smaller than the minimum the caller allows
        assert min(b - a for a, b in pieces) >= chunks.MIN_CHUNK
    else:
        assert pieces == [(0, n)]


@pytest.mark.parametrize("per_thread", [1, 4])
def test_every_row_is_worked_once_and_threads_share_the_pieces(per_thread, two_threads,
                                                               monkeypatch):
    monkeypatch.setattr(chunks, "CHUNKS_PER_THREAD", per_thread)
    n = 4000
    hits = np.zeros(n, dtype=np.int64)
    workers: set[str] = set()
    lock = threading.Lock()
    gate = threading.Barrier(2, timeout=5.0)

    def work(a: int, b: int) -> None:
        me = threading.current_thread().name
        with lock:
            first = me not in workers
            workers.add(me)
        if first:  # each thread's first piece waits for the other's: both take part
            with contextlib.suppress(threading.BrokenBarrierError):
                gate.wait()
        hits[a:b] += 1

    chunks.in_chunks(n, work)
    assert (hits == 1).all()
    assert len(workers) == 2


def test_a_slow_thread_takes_fewer_pieces(two_threads, monkeypatch):
    """The calling thread stalls on its first piece: the pool's thread does the rest."""
    monkeypatch.setattr(chunks, "CHUNKS_PER_THREAD", 4)
    n = 800
    _, pieces = chunks.chunk_bounds(n)
    done_by: dict[int, str] = {}
    caller = threading.current_thread().name
    others_done = threading.Event()

    def work(a: int, b: int) -> None:
        me = threading.current_thread().name
        if me == caller:  # as if the core were taken by another process
            others_done.wait(10.0)
        done_by[a] = me
        if len(done_by) == len(pieces) - 1:
            others_done.set()

    chunks.in_chunks(n, work)
    assert sorted(done_by) == [a for a, _ in pieces]
    assert sum(v == caller for v in done_by.values()) == 1


def test_a_failure_in_a_piece_is_raised_and_stops_new_pieces(two_threads, monkeypatch):
    monkeypatch.setattr(chunks, "CHUNKS_PER_THREAD", 4)
    started: list[int] = []
    boom = threading.Event()

    def work(a: int, b: int) -> None:
        started.append(a)
        if a == 0:
            boom.set()
            raise ValueError("piece 0 failed")
        boom.wait(10.0)
        threading.Event().wait(0.05)

    with pytest.raises(ValueError, match="piece 0 failed"):
        chunks.in_chunks(4000, work)
    assert len(started) < len(chunks.chunk_bounds(4000)[1])
