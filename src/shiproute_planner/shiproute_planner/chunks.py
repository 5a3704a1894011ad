"""Population work split over the planner's threads: the compiled kernels release the GIL,
so one chunk per core runs in parallel on a shared pool of Python threads."""

from __future__ import annotations

import itertools
import os
import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from .threads import planner_threads

MIN_CHUNK = 16  # rows per thread below which one thread does it all
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


def in_chunks(n: int, work: Callable[[int, int], None], min_chunk: int = MIN_CHUNK) -> None:
    """Run work(a, b) over 0..n in one chunk per thread (`threads.planner_threads`); the
    calling thread takes the last chunk instead of waiting idle."""
    k = max(1, min(planner_threads(), N_THREADS, n // max(min_chunk, 1)))
    if k == 1:
        work(0, n)
        return
    bounds = np.linspace(0, n, k + 1).astype(int)
    pairs = list(itertools.pairwise(bounds))
    pool = _pool()
    futures = [pool.submit(work, int(a), int(b)) for a, b in pairs[:-1]]
    try:
        work(int(pairs[-1][0]), int(pairs[-1][1]))
    finally:  # never leave a chunk running on arrays the caller is about to drop
        for f in futures:
            f.result()
