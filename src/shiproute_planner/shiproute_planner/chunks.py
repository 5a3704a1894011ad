"""Population work split over the planner's threads: the compiled kernels release the GIL,
so chunks run in parallel on a shared pool of Python threads. A thread takes the next piece
when it is done with its last: a pool thread that starts late (its core taken by another
process) leaves its piece to the caller instead of holding the population up. One piece per
thread by default: more, smaller pieces measured slower on the loaded 2-core machine (each
costs a dispatch that needs the GIL)."""

from __future__ import annotations

import itertools
import os
import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor

from .threads import planner_threads

MIN_CHUNK = 16  # rows per thread below which one thread does it all
CHUNKS_PER_THREAD = 1  # pieces per thread, taken in turn by whichever thread is free
N_THREADS = max(1, min(4, os.cpu_count() or 1))
_LOCK = threading.Lock()
_POOL: ThreadPoolExecutor | None = None


def _pool() -> ThreadPoolExecutor:
    """This module's pool, made on first use. Not `ship.fast`'s: a chunk may call the fast
    ship model, which fans out on its own pool; one shared pool could leave every worker
    waiting on work queued behind it."""
    global _POOL
    with _LOCK:
        if _POOL is None:
            _POOL = ThreadPoolExecutor(max_workers=N_THREADS, thread_name_prefix="shiproute-eval")
        return _POOL


def _forget_pool_in_child() -> None:
    """A forked child has no worker threads: drop the inherited pool (and lock)."""
    global _POOL, _LOCK
    _POOL = None
    _LOCK = threading.Lock()


os.register_at_fork(after_in_child=_forget_pool_in_child)


def chunk_bounds(n: int, min_chunk: int = MIN_CHUNK) -> tuple[int, list[tuple[int, int]]]:
    """(threads, pieces (a, b) covering 0..n in order) of `in_chunks`: up to
    `CHUNKS_PER_THREAD` pieces per thread, none under `min_chunk` rows unless there is one."""
    most = n // max(min_chunk, 1)
    k = max(1, min(planner_threads(), N_THREADS, most))
    if k == 1:
        return 1, [(0, n)]
    pieces = max(k, min(k * CHUNKS_PER_THREAD, most))
    bounds = [i * n // pieces for i in range(pieces + 1)]
    return k, list(itertools.pairwise(bounds))


def in_chunks(n: int, work: Callable[[int, int], None], min_chunk: int = MIN_CHUNK) -> None:
    """Run work(a, b) over 0..n in pieces (`chunk_bounds`) on up to `planner_threads()`
    threads, the calling thread one of them; each takes the next piece when free. After a
    failure no new piece starts; the first error is raised once every thread has stopped."""
    k, pairs = chunk_bounds(n, min_chunk)
    if k == 1:
        work(0, n)
        return
    pending = iter(pairs)
    lock = threading.Lock()
    failed = threading.Event()

    def drain() -> None:
        while not failed.is_set():
            with lock:
                piece = next(pending, None)
            if piece is None:
                return
            try:
                work(*piece)
            except BaseException:
                failed.set()
                raise

    pool = _pool()
    futures = [pool.submit(drain) for _ in range(k - 1)]
    try:
        drain()
    finally:  # never leave a chunk running on arrays the caller is about to drop
        for f in futures:
            f.result()
