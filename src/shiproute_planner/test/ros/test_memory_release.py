"""The planner node's memory release: raster pages handed back intact, RSS flat over plans."""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
from shiproute_planner.ros.memory_release import (
    drop_file_pages,
    read_only_file_maps,
    resident_kib,
)

linux_only = pytest.mark.skipif(not Path("/proc/self/smaps").exists(), reason="needs Linux /proc")


def test_only_read_only_npy_maps_under_the_directory_are_chosen(tmp_path: Path) -> None:
    data = tmp_path / "data"
    maps = tmp_path / "maps"
    maps.write_text(textwrap.dedent(f"""\
        7f0000000000-7f0000100000 r--s 00000000 08:01 11 {data}/landmask.npy
        7f0000100000-7f0000200000 rw-s 00000000 08:01 12 {data}/written.npy
        7f0000200000-7f0000300000 r--p 00000000 08:01 13 {data}/notes.json
        7f0000300000-7f0000400000 r--s 00000000 08:01 14 {tmp_path}/elsewhere/depth.npy
        7f0000400000-7f0000500000 rw-p 00000000 00:00 0
        """))
    assert list(read_only_file_maps(str(data), str(maps))) == [(0x7F0000000000, 0x7F0000100000)]


@linux_only
def test_dropped_pages_leave_the_process_and_the_values_read_back(tmp_path: Path) -> None:
    values = np.random.default_rng(7).standard_normal((2048, 2048)).astype(np.float32)  # 16 MiB
    np.save(tmp_path / "raster.npy", values)
    mapped = np.load(tmp_path / "raster.npy", mmap_mode="r")
    total = float(np.sum(mapped, dtype=np.float64))  # touches every page
    (start, end), = read_only_file_maps(str(tmp_path))
    assert resident_kib(start, end) >= 0.9 * values.nbytes / 1024
    dropped_mb = drop_file_pages(str(tmp_path))
    assert dropped_mb >= 0.9 * values.nbytes / 2**20
    assert resident_kib(start, end) <= 64  # a few pages at most
    assert float(np.sum(mapped, dtype=np.float64)) == total


_PLANS = """
import json, sys
from shiproute_planner.planning import plan_voyage
from shiproute_planner.ros.memory_release import release_after_plan
from shiproute_weather.sampling.sampler import ForecastSampler
from shiproute_weather.scenarios.catalogue import scenario_dataset

forecast = ForecastSampler(scenario_dataset("storm_march"))
rss = []
for k in range(int(sys.argv[1])):
    plan_voyage("Busan", "Long Beach", "2026-03-03T18:00Z", "2026-03-16T18:00Z",
                "container_4600teu", forecast, budget_s=0.3, seed=k)
    rss.append(release_after_plan(collect=k == 0).resident_mb)
print(json.dumps(rss))
"""


@linux_only
@pytest.mark.slow
def test_resident_memory_is_flat_over_repeated_plans() -> None:
    """The issue's soak target per node, end - start <= 10 MB, over plans 2..8 in a process
    of its own (the first plan loads land, depth and compiled kernels once)."""
    out = subprocess.run([sys.executable, "-c", _PLANS, "8"], capture_output=True, text=True,
                         timeout=600, check=True)
    rss = json.loads(out.stdout.strip().splitlines()[-1])
    assert max(rss[1:]) - rss[1] <= 10.0, rss
