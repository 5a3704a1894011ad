"""Seed pool shared by concurrent writers (fleet workers): nothing lost, nothing corrupt.

Without the lock, each writer reads the pool, adds its seed and renames its copy over the
file, so a writer that read before another's rename drops that seed (lost update): with 4
processes x 25 offers that loses seeds nearly every run, which this test would catch."""

from __future__ import annotations

import json
import multiprocessing as mp

from shiproute_planner.ga.pool import Seed, SeedPool, pool_key

N_PROC, N_OFFERS = 4, 25


def _seed(key: str, value: float) -> Seed:
    return Seed(key, (129.0, 200.0), (35.1, 33.7), (70.0,), "fuel", value, 0.0, value, "t")


def _writer(directory: str, proc: int, start) -> None:
    start.wait()
    pool = SeedPool(directory)
    for k in range(N_OFFERS):
        # a key of its own (must survive) and a shared key improved by every writer
        pool.offer(_seed(pool_key(f"P{proc:02d}", f"K{k:03d}", 1), 500.0 + k))
        pool.offer(_seed(pool_key("SHARE", "DPORT", 1), 1000.0 - (proc * N_OFFERS + k)))


def test_concurrent_writers_lose_nothing(tmp_path):
    ctx = mp.get_context("fork")
    start = ctx.Event()
    procs = [ctx.Process(target=_writer, args=(str(tmp_path), p, start)) for p in range(N_PROC)]
    for p in procs:
        p.start()
    start.set()
    for p in procs:
        p.join(60)
        assert p.exitcode == 0
    data = json.loads((tmp_path / "seed_pool.json").read_text())  # valid JSON: not corrupt
    seeds = data["seeds"]
    assert len(seeds) == N_PROC * N_OFFERS + 1
    for p in range(N_PROC):
        for k in range(N_OFFERS):
            assert seeds[pool_key(f"P{p:02d}", f"K{k:03d}", 1)]["objective_value"] == 500.0 + k
    # the best offer to the shared key is the last writer's last one: 1000 - (4 x 25 - 1)
    best = SeedPool(tmp_path).get(pool_key("SHARE", "DPORT", 1))
    assert best is not None and best.objective_value == 1000.0 - (N_PROC * N_OFFERS - 1)
    assert not list(tmp_path.glob("*.tmp"))  # no temp file left behind
