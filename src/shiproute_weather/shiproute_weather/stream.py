"""Two-pass, bounded-memory path from one NetCDF file to slices.

Pass 1 loads, normalises and validates the file in blocks of valid times (nothing is kept);
pass 2 repeats that and yields the slices. Peak memory is one block instead of the whole
cycle, so a publisher holds little more than its middleware history. The file is read twice.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import replace
from pathlib import Path

import numpy as np
import xarray as xr

from .combine import subset
from .coords import rename_coords
from .cycle_builder import CycleConfig
from .errors import ForecastFileError, GridError, WeatherError
from .loaders import NETCDF_CHUNK_CACHE_BYTES, _decode_in_place, detect_format
from .normalise import to_canonical
from .slices import CycleInfo, SliceData, cycle_info, dataset_to_slices, snap_grid
from .validate import validate

BLOCK_TIMES = 16


def streamable(paths: list[str], cfg: CycleConfig) -> bool:
    """One NetCDF file and no time thinning: the streaming path applies."""
    return (len(paths) == 1 and cfg.slice_interval_s <= 0 and cfg.grid_stride == 1
            and Path(paths[0]).exists() and detect_format(Path(paths[0])) == "netcdf")


def _blocks(path: str, cfg: CycleConfig) -> Iterator[xr.Dataset]:
    import netCDF4

    netCDF4.set_chunk_cache(NETCDF_CHUNK_CACHE_BYTES, 61, 0.75)
    try:
        raw = xr.open_dataset(path, engine="netcdf4", decode_timedelta=True,
                              mask_and_scale=False)
    except Exception as exc:
        raise ForecastFileError(path, f"cannot be read as NetCDF ({exc})") from exc
    with raw:
        lazy = rename_coords(raw, path)
        n = lazy.sizes["time"]
        attrs: dict[str, str] | None = None
        last_t = None
        for i in range(0, min(n, cfg.max_slices), BLOCK_TIMES):
            sub = lazy.isel(time=slice(i, min(i + BLOCK_TIMES, n, cfg.max_slices))).copy()
            try:
                for name in list(sub.data_vars):
                    sub[name] = _decode_in_place(sub[name]) if sub[name].ndim >= 2 else \
                        sub[name].load()
            except Exception as exc:
                raise ForecastFileError(path, f"unreadable data in valid times {i}.. ({exc})") \
                    from exc
            block = to_canonical(sub, path)
            if attrs is None:
                attrs = dict(block.attrs)
                if cfg.cycle_id:
                    attrs["cycle_id"] = cfg.cycle_id
            block.attrs.update(attrs)
            validate(block, path, cfg.required)
            t = block["time"].values
            if last_t is not None and t[0] <= last_t:
                raise GridError(path, "valid times are not ascending across the file")
            last_t = t[-1]
            if cfg.box is not None:
                block = subset(block, cfg.box)
            yield snap_grid(block)


def stream_cycle(path: str, cfg: CycleConfig) -> CycleInfo:
    """Pass 1: validate the whole file block by block; returns the cycle announcement."""
    times: list[np.ndarray] = []
    first: xr.Dataset | None = None
    for block in _blocks(path, cfg):
        if first is None:
            first = block.isel(time=[0])
        times.append(block["time"].values)
    if first is None:
        raise WeatherError(f"{path}: no valid time")
    if first.nbytes > cfg.max_slice_bytes:
        raise GridError(path, f"one slice is {first.nbytes} B, above the {cfg.max_slice_bytes} B "
                              "bound; set a region or grid_stride")
    t = np.concatenate(times).astype("datetime64[ns]").astype(np.int64)
    one = cycle_info(first, [path])
    step = float((t[1] - t[0]) / 1e9) if t.size > 1 else 0.0
    return replace(one, first_valid_time_ns=int(t[0]), last_valid_time_ns=int(t[-1]),
                   step_s=step, slice_count=int(t.size))


def stream_slices(path: str, cfg: CycleConfig, info: CycleInfo) -> Iterator[SliceData]:
    """Pass 2: the slices, block by block, numbered over the whole cycle of `info`."""
    k = 0
    for block in _blocks(path, cfg):
        for s in dataset_to_slices(block):
            yield replace(s, slice_index=k, slice_count=info.slice_count)
            k += 1
    if k != info.slice_count:
        raise WeatherError(f"{path}: changed while publishing ({k} slices, expected "
                           f"{info.slice_count})")
