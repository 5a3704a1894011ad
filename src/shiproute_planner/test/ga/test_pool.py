"""Seed pool: persistence across instances, better-of rule, clear errors on bad files."""

from __future__ import annotations

import pytest
from shiproute_planner.errors import SeedPoolError
from shiproute_planner.ga.pool import Seed, SeedPool, pool_key


def _seed(value: float, violation: float = 0.0) -> Seed:
    return Seed(pool_key("KRPUS", "USLGB", 3), (129.0, 200.0, 241.8), (35.1, 45.0, 33.7),
                (70.0, 72.0), "fuel", value, violation, value, "test", genes=(1.0, 2.0))


def test_pool_persists_and_keeps_the_better(tmp_path):
    pool = SeedPool(tmp_path)
    assert pool.get(pool_key("KRPUS", "USLGB", 3)) is None
    assert pool.offer(_seed(650.0))
    again = SeedPool(tmp_path)  # a new process/instance reads the same file
    got = again.get(pool_key("krpus", "uslgb", 3))
    assert got is not None and got.objective_value == 650.0 and got.genes == (1.0, 2.0)
    assert not again.offer(_seed(700.0))  # worse: kept out
    assert not again.offer(_seed(600.0, violation=1.0))  # infeasible never beats feasible
    assert again.offer(_seed(640.0))
    assert SeedPool(tmp_path).get(pool_key("KRPUS", "USLGB", 3)).objective_value == 640.0
    assert SeedPool(tmp_path).get(pool_key("KRPUS", "USLGB", 4)) is None  # other month


def test_bad_pool_file(tmp_path):
    (tmp_path / "seed_pool.json").write_text("{not json")
    with pytest.raises(SeedPoolError, match="unreadable"):
        SeedPool(tmp_path).get("x")
