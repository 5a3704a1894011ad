"""Benchmark part: a two-source cycle (wind and waves from one file, currents from another on
its own 1 deg grid and 6-hourly step) loaded, combined, validated and encoded as the weather
node does. Run in its own process so its memory peak is its own: prints one JSON object."""

from __future__ import annotations

import json
import resource
import time
from pathlib import Path

import numpy as np


def make_sources(scenario: str = "storm_march") -> tuple[Path, Path]:
    """The two files, derived once from a bundled scenario (not timed)."""

    from ..contract import canonical as cv
    from ..scenarios.catalogue import scenario_dataset, scenario_path

    base = scenario_path(scenario)
    wind_waves = base.with_name(f"{base.stem}.bench-windwaves.nc")
    currents = base.with_name(f"{base.stem}.bench-currents-1deg-6h.nc")
    if not (wind_waves.exists() and currents.exists()):
        ds = scenario_dataset(scenario)
        keep = [n for n in cv.present_variables(ds) if n not in (cv.CURRENT_U, cv.CURRENT_V)]
        enc = {n: {"dtype": "float32"} for n in keep}
        ds[keep].to_netcdf(wind_waves.with_suffix(".tmp"), encoding=enc)
        cur = ds[[cv.CURRENT_U, cv.CURRENT_V]].isel(time=slice(0, None, 2),
                                                    latitude=slice(0, None, 2),
                                                    longitude=slice(0, None, 2))
        cur = cur.assign_coords(longitude=((cur["longitude"] + 180.0) % 360.0) - 180.0)
        cur = cur.sortby("longitude")  # a -180..180 product beside a 0..360 one
        cur.to_netcdf(currents.with_suffix(".tmp"))
        wind_waves.with_suffix(".tmp").rename(wind_waves)
        currents.with_suffix(".tmp").rename(currents)
    return wind_waves, currents


def main() -> None:
    from ..ingest.cycle_builder import CycleConfig, build_cycle
    from ..ingest.stream import warm_array_backends
    from ..ros.convert import DEFAULT_SLICE_ENCODING, slice_to_msg

    a, b = make_sources()
    warm_array_backends()  # as the weather node does at start
    t0 = time.perf_counter()
    c0 = time.process_time()
    info, slices, _ = build_cycle([str(a), str(b)], CycleConfig())
    n = 0
    for k in range(len(slices)):
        s, slices[k] = slices[k], None  # type: ignore[call-overload]
        slice_to_msg(s, encoding=DEFAULT_SLICE_ENCODING)
        n += 1
    dt = time.perf_counter() - t0
    cpu = time.process_time() - c0
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    print(json.dumps({"multi_source_load_s": round(dt, 3),
                      "multi_source_load_cpu_s": round(cpu, 3), "multi_source_slices": n,
                      "multi_source_fields": len(info.fields),
                      "multi_source_peak_rss_mb": round(float(np.float64(rss)), 1)}))


if __name__ == "__main__":
    main()
