"""Benchmark part: what a 20-member cycle costs on the wire and in each node, within the weather
node's default budget. The members are the bundled storm (16 days, 3-hourly) with its wind
scaled by 1 + 0.1 N(0, 1) per member (Hs by the square): a test ensemble, not a forecast. The
budget keeps one valid time in k (`cycle_builder.thin`); the members are built on those times
only (20 members of all 129 times would take 3.6 GB to build just to be thinned) and the uncut
cycle's size is computed. Run in its own process (its own memory peak): prints one JSON
object."""

from __future__ import annotations

import json
import time
from dataclasses import replace
from typing import Any

import numpy as np

#: members of the benchmark ensemble (ECMWF ENS has 51, GEFS 31; the issue's target is 20)
MEMBERS = 20


def perturbed_ensemble(base: Any, members: int, seed: int = 19) -> Any:
    """`members` members of a deterministic dataset (member 0 is `base` itself)."""
    from ..contract import canonical as cv
    from ..contract.members import stack_members

    rng = np.random.default_rng(seed)
    out = [base]
    for _ in range(1, members):
        f = float(np.clip(1.0 + 0.1 * rng.standard_normal(), 0.7, 1.3))
        m = base.copy(deep=True)
        for n in (cv.WIND_U, cv.WIND_V):
            m[n].values *= f
        for n in (cv.WAVE_HS, cv.WIND_WAVE_HS):
            if n in m:
                m[n].values = np.minimum(m[n].values * f * f, 29.0)
        out.append(m)
    return stack_members(out, [str(k) for k in range(members)], kind="ensemble")


def _peak_rss_mb() -> float:
    """This process's peak resident memory (VmHWM: unlike ru_maxrss, not inherited from the
    parent that started it)."""
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmHWM:"):
                return round(int(line.split()[1]) / 1024.0, 1)
    return float("nan")


def main(scenario: str = "storm_march", max_slices: int = 0, grid_stride: int = 1) -> dict:
    """Budget figures of a 20-member cycle (see the module docstring) with the node's default
    budget, or `max_slices` / `grid_stride` as the node's parameters would set them."""
    from ..contract.canonical import present_variables
    from ..contract.members import member_count
    from ..ingest.cycle_builder import CycleConfig, thin
    from ..ros.convert import slice_to_msg, wire_bytes
    from ..scenarios.catalogue import scenario_dataset
    from ..wire.slices import dataset_to_slices

    cfg = CycleConfig(grid_stride=grid_stride)
    if max_slices > 0:
        cfg = replace(cfg, max_slices=max_slices)
    full = scenario_dataset(scenario)
    n_t = full.sizes["time"]
    stride = -(-n_t // max(1, cfg.max_slices // MEMBERS))
    full_bytes = MEMBERS * n_t * full.sizes["latitude"] * full.sizes["longitude"] * len(
        present_variables(full)) * 2
    ds = perturbed_ensemble(full.isel(time=slice(0, None, stride)).load(), MEMBERS)
    t0 = time.perf_counter()
    kept, notes = thin(ds, cfg)
    cycle_bytes = 0
    slices = 0
    for s in dataset_to_slices(kept):
        cycle_bytes += wire_bytes(slice_to_msg(s, encoding="packed16"))
        slices += 1
    encode_s = time.perf_counter() - t0
    cells = kept.sizes["latitude"] * kept.sizes["longitude"]
    n_fields = len(present_variables(kept))
    times_kept = kept.sizes["time"]
    t = kept["time"].values
    return {"ensemble_members": member_count(kept), "ensemble_slices": slices,
            "ensemble_valid_times_per_member": times_kept,
            "ensemble_source_valid_times": n_t,
            "ensemble_step_h": float((t[1] - t[0]) / np.timedelta64(1, "h")),
            "ensemble_full_cycle_bytes": full_bytes,
            "ensemble_cycle_bytes": cycle_bytes,
            "ensemble_slice_bytes": cycle_bytes // max(slices, 1),
            "ensemble_max_slices": cfg.max_slices,
            "ensemble_weather_history_mb": round(cycle_bytes / 2**20, 1),
            "ensemble_planner_dataset_mb": round(
                member_count(kept) * times_kept * cells * n_fields * 4 / 2**20, 1),
            "ensemble_encode_s": round(encode_s, 3),
            "ensemble_budget_notes": [*notes, f"one valid time in {stride} kept to fit "
                                              f"max_slices {cfg.max_slices}"],
            "ensemble_grid": f"{kept.sizes['latitude']} x {kept.sizes['longitude']}",
            "ensemble_bench_peak_rss_mb": _peak_rss_mb()}


if __name__ == "__main__":
    import sys

    args = [int(x) for x in sys.argv[1:3]]  # optional: max_slices grid_stride
    print(json.dumps(main("storm_march", *args)))
