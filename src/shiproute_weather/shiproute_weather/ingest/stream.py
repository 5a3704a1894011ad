"""Block-wise path from one NetCDF file to validated slices with bounded peak memory.

The file is read, normalised and validated in blocks of valid times, so no whole-variable
arrays or decoder copies exist; the slices hold per-block arrays that are freed as a
publisher drops them, leaving little more than the middleware history.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import replace
from pathlib import Path
from typing import TypeVar

import numpy as np
import xarray as xr

from ..contract.record import load_notes
from ..contract.validate import validate
from ..errors import ForecastFileError, GridError, WeatherError
from ..wire.slices import CycleInfo, SliceData, cycle_info, dataset_to_slices, snap_grid
from .combine import subset
from .coords import rename_coords
from .cycle_builder import CycleConfig
from .loaders import NETCDF_CHUNK_CACHE_BYTES, decode_variables, detect_format
from .normalise import to_canonical
from .outliers import masked_counts

#: Valid times per block. A block's memory is freed only once all its slices are published,
#: so while publishing the process briefly holds one block twice (slices + middleware
#: history): 16 instead of 32 halves that extra peak for a small per-block overhead.
BLOCK_TIMES = 16

T = TypeVar("T")


def streamable(paths: list[str], cfg: CycleConfig) -> bool:
    """One deterministic NetCDF file with waves (or no wind), no time thinning: the streaming
    path applies.

    A wind-only file is loaded whole: its waves are grown from the wind through all of its
    valid times (`wind_waves`)."""
    return (len(paths) == 1 and cfg.slice_interval_s <= 0 and cfg.grid_stride == 1
            and Path(paths[0]).exists() and detect_format(Path(paths[0])) == "netcdf"
            and not _wind_without_waves(paths[0]) and not _has_members(paths[0]))


def _has_members(path: str) -> bool:
    """Whether a NetCDF file has an ensemble member dimension of more than one member (read
    lazily): such a file is loaded whole, so every member's slices are made and counted."""
    from .normalise import MEMBER_DIMS

    try:
        with xr.open_dataset(path, engine="netcdf4", decode_times=False) as raw:
            return any(raw.sizes.get(d, 1) > 1 for d in MEMBER_DIMS)
    except Exception:
        return False  # the block-wise path reports what is wrong with the file


def _wind_without_waves(path: str) -> bool:
    """Whether a NetCDF file maps to wind but to no wave height (read lazily: names only)."""
    from ..contract import canonical as cv
    from .normalise import mapped_variables

    try:
        with xr.open_dataset(path, engine="netcdf4", decode_times=False) as raw:
            found = mapped_variables(raw)
    except Exception:
        return False  # the block-wise path reports what is wrong with the file
    waves = {cv.WAVE_HS, cv.WIND_WAVE_HS, cv.SWELL_HS}
    return cv.WIND_U in found and not found & waves


def _blocks(path: str, cfg: CycleConfig) -> Iterator[tuple[int, xr.Dataset]]:
    """(valid times the file yields in all, block) for each block of valid times."""
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
        total = min(n, cfg.max_slices)
        attrs: dict[str, str] | None = None
        last_t = None
        for i in range(0, min(n, cfg.max_slices), BLOCK_TIMES):
            try:
                sub = decode_variables(
                    lazy.isel(time=slice(i, min(i + BLOCK_TIMES, n, cfg.max_slices))))
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
            yield total, snap_grid(block)


def load_slices(path: str, cfg: CycleConfig
                ) -> tuple[CycleInfo, list[SliceData], list[str]]:
    """Read, normalise and validate the file block by block into slices (one pass).

    Nothing is published before the whole file has been validated. Each slice's arrays are
    views into its block, so a caller that drops slices as it publishes them frees the
    memory block by block (the middleware history then takes its place). The grid is thinned
    like `cycle_builder.thin` when a slice would exceed `cfg.max_slice_bytes`.
    """
    return load_encoded(path, cfg, _keep)


def _keep(s: SliceData) -> SliceData:
    return s


def load_encoded(path: str, cfg: CycleConfig, encode: Callable[[SliceData], T]
                 ) -> tuple[CycleInfo, list[T], list[str]]:
    """`load_slices` with each slice passed through `encode` as soon as its block is read.

    The float32 slices of a block are dropped once encoded, so a caller that encodes to the
    wire form (half the bytes when packed) never holds the whole cycle as float32: the peak of
    a reload is the encoded cycle plus one block instead of the float32 cycle beside it.
    Each slice handed to `encode` already carries its final index and the cycle's count.
    """
    out: list[T] = []
    first: xr.Dataset | None = None
    stride = 1
    notes: list[str] = []
    masked: dict[str, int] = {}
    times: list[int] = []
    for total, block in _blocks(path, cfg):
        for name, k in masked_counts(block).items():
            masked[name] = masked.get(name, 0) + k
        if first is None:
            per_node = 4 * len(block.data_vars)
            ny, nx = block.sizes["latitude"], block.sizes["longitude"]
            while -(-ny // stride) * -(-nx // stride) * per_node > cfg.max_slice_bytes:
                stride += 1
            if stride > 1:
                notes.append(f"grid thinned by {stride} to keep slices <= "
                             f"{cfg.max_slice_bytes} B")
        if stride > 1:
            block = snap_grid(block.isel(latitude=slice(None, None, stride),
                                         longitude=slice(None, None, stride)))
        if first is None:
            first = block.isel(time=[0])
            for name in masked:
                first[name].attrs["masked_outliers"] = 0  # the totals are set below
        for sl in dataset_to_slices(block):
            times.append(sl.valid_time_ns)
            out.append(encode(replace(sl, slice_index=len(out), slice_count=total)))
        del block
    if first is None:
        raise WeatherError(f"{path}: no valid time")
    n = len(out)
    if n != total:  # every block yields all its valid times: a mismatch is a loader bug
        raise WeatherError(f"{path}: read {n} valid times, expected {total}")
    t = np.array(times, dtype=np.int64)
    step = float((t[1] - t[0]) / 1e9) if n > 1 else 0.0
    for name, k in masked.items():
        first[name].attrs["masked_outliers"] = k
    report = load_notes(first)
    info = replace(cycle_info(first, [path]), first_valid_time_ns=int(t[0]),
                   last_valid_time_ns=int(t[-1]), step_s=step, slice_count=n,
                   notes=tuple(report))
    return info, out, report + notes


def warm_array_backends() -> None:
    """Let xarray import the array libraries it looks up on its first copy (dask's array module
    when dask is installed, about 1 s), so a process's first forecast load is timed as a load."""
    import numpy as np
    import xarray as xr

    xr.Dataset({"x": ("t", np.zeros(1, np.float32))}).copy(deep=True)
