"""Block-wise path from one NetCDF file to validated slices with bounded peak memory.

The file is read, normalised and validated in blocks of valid times, so no whole-variable
arrays or decoder copies exist; the slices hold per-block arrays that are freed as a
publisher drops them, leaving little more than the middleware history.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass, replace
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
from .stream_plan import StreamPlan, plan_stream

#: Valid times per block. A block's memory is freed only once all its slices are published,
#: so while publishing the process briefly holds one block twice (slices + middleware
#: history): 16 instead of 32 halves that extra peak for a small per-block overhead.
BLOCK_TIMES = 16

T = TypeVar("T")


def streamable(paths: list[str], cfg: CycleConfig) -> bool:
    """One NetCDF file (deterministic or an ensemble) with waves (or no wind), no time
    thinning: the streaming path applies.

    A wind-only file is loaded whole: its waves are grown from the wind through all of its
    valid times (`wind_waves`)."""
    return (len(paths) == 1 and cfg.slice_interval_s <= 0 and cfg.grid_stride == 1
            and Path(paths[0]).exists() and detect_format(Path(paths[0])) == "netcdf"
            and not _wind_without_waves(paths[0]))


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


@dataclass(frozen=True)
class Block:
    """One member's block of valid times, canonical (deterministic dims), validated."""

    member: int  # 0-based member of the cycle
    data: xr.Dataset


def _member_blocks(lazy: xr.Dataset, path: str, cfg: CycleConfig, plan: StreamPlan,
                   attrs: dict[str, str]) -> Iterator[Block]:
    """Blocks of BLOCK_TIMES valid times of each member in turn (member-major order)."""
    for m, raw_member in enumerate(plan.members or (-1,)):
        last_t = None
        for i in range(0, len(plan.times), BLOCK_TIMES):
            sel: dict[str, list[int]] = {"time": list(plan.times[i:i + BLOCK_TIMES])}
            if plan.member_dim:  # one member: its dim of size 1 is dropped by to_canonical
                sel[plan.member_dim] = [raw_member]
            try:
                sub = decode_variables(lazy.isel(sel))
            except Exception as exc:
                raise ForecastFileError(path, f"unreadable data in valid times {i}.. ({exc})") \
                    from exc
            block = to_canonical(sub, path)
            if not attrs:  # the first block's attrs (cycle id, source) hold for every block
                attrs.update(block.attrs)
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
            yield Block(m, snap_grid(block))


def _blocks(path: str, cfg: CycleConfig) -> Iterator[tuple[StreamPlan, Block]]:
    """(the cycle's plan, block) for each member's block of valid times."""
    import netCDF4

    netCDF4.set_chunk_cache(NETCDF_CHUNK_CACHE_BYTES, 61, 0.75)
    try:
        raw = xr.open_dataset(path, engine="netcdf4", decode_timedelta=True,
                              mask_and_scale=False)
    except Exception as exc:
        raise ForecastFileError(path, f"cannot be read as NetCDF ({exc})") from exc
    with raw:
        lazy = rename_coords(raw, path)
        plan = plan_stream(lazy, path, cfg)
        for block in _member_blocks(lazy, path, cfg, plan, {}):
            yield plan, block


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


def _grid_stride(block: xr.Dataset, cfg: CycleConfig) -> int:
    """Smallest grid stride that keeps one float32 slice within `cfg.max_slice_bytes`."""
    per_node = 4 * len(block.data_vars)
    ny, nx = block.sizes["latitude"], block.sizes["longitude"]
    stride = 1
    while -(-ny // stride) * -(-nx // stride) * per_node > cfg.max_slice_bytes \
            and -(-ny // stride) * -(-nx // stride) > 4:
        stride += 1
    return stride


def load_encoded(path: str, cfg: CycleConfig, encode: Callable[[SliceData], T]
                 ) -> tuple[CycleInfo, list[T], list[str]]:
    """`load_slices` with each slice passed through `encode` as soon as its block is read.

    The file is read one member and BLOCK_TIMES valid times at a time (an ensemble member by
    member), and the float32 slices of a block are dropped once encoded: a caller that encodes
    to the wire form (half the bytes when packed) never holds the cycle as float32, and the
    peak of a load is the encoded cycle plus one block of one member. Each slice handed to
    `encode` already carries its final index, member and the cycle's counts.
    """
    out: list[T] = []
    first: xr.Dataset | None = None
    plan: StreamPlan | None = None
    stride = 1
    notes: list[str] = []
    masked: dict[str, int] = {}
    times: list[int] = []
    for plan, blk in _blocks(path, cfg):
        block = blk.data
        for name, k in masked_counts(block).items():
            masked[name] = masked.get(name, 0) + k
        if first is None:
            notes.extend(plan.notes)
            stride = _grid_stride(block, cfg)
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
        label = plan.labels[blk.member] if plan.labels else ""
        for sl in dataset_to_slices(block):
            _check_member_time(path, blk.member, len(times), times, sl.valid_time_ns, len(out))
            out.append(encode(replace(sl, slice_index=len(out), slice_count=plan.slice_count,
                                      member=blk.member, member_count=plan.member_count,
                                      member_label=label)))
        del block
    if first is None or plan is None:
        raise WeatherError(f"{path}: no valid time")
    return _cycle_of(path, first, plan, out, times, masked, notes)


def _check_member_time(path: str, member: int, n_times: int, times: list[int], t_ns: int,
                       index: int) -> None:
    """Collect member 0's valid times; every later member must repeat them."""
    if member == 0:
        times.append(t_ns)
    elif t_ns != times[index - member * n_times]:
        raise GridError(path, f"member {member} has another valid time than member 0")


def _cycle_of(path: str, first: xr.Dataset, plan: StreamPlan, out: list[T], times: list[int],
              masked: dict[str, int], notes: list[str]
              ) -> tuple[CycleInfo, list[T], list[str]]:
    """The cycle announcement of a streamed load, after every block was read."""
    n = len(out)
    if n != plan.slice_count:  # every block yields all its valid times: else a loader bug
        raise WeatherError(f"{path}: read {n} slices, expected {plan.slice_count}")
    t = np.array(times, dtype=np.int64)
    step = float((t[1] - t[0]) / 1e9) if t.size > 1 else 0.0
    for name, k in masked.items():
        first[name].attrs["masked_outliers"] = k
    if plan.ensemble_note:
        first.attrs["ensemble"] = plan.ensemble_note
    report = load_notes(first)
    info = replace(cycle_info(first, [path]), first_valid_time_ns=int(t[0]),
                   last_valid_time_ns=int(t[-1]), step_s=step, slice_count=n,
                   notes=tuple(report + notes), member_count=plan.member_count,
                   member_labels=plan.labels,
                   member_kind="ensemble" if plan.member_count > 1 else "")
    return info, out, report + notes


def warm_array_backends() -> None:
    """Let xarray import the array libraries it looks up on its first copy (dask's array module
    when dask is installed, about 1 s), so a process's first forecast load is timed as a load."""
    import numpy as np
    import xarray as xr

    xr.Dataset({"x": ("t", np.zeros(1, np.float32))}).copy(deep=True)
