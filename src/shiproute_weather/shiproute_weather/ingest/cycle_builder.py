"""Build a publishable cycle from forecast files: load, validate, subset, thin, bound sizes."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field, replace

import numpy as np
import xarray as xr

from ..contract import canonical as cv
from ..contract.members import MEMBER_DIM, member_count, member_labels, select_member
from ..contract.record import load_notes
from ..errors import SliceError
from ..wire.slices import CycleInfo, SliceData, cycle_info, dataset_to_slices, snap_grid
from .combine import Box, subset
from .loaders import open_forecast
from .members import open_members

#: Default bound on one ForecastSlice message (field bytes). A 0.5 deg North Pacific grid
#: (105 x 261) with 13 fields is 1.43 MB; larger sources are thinned (grid stride) to fit.
MAX_SLICE_BYTES = 4_000_000
#: Default bound on slices per cycle = depth of the transient-local slice history.
MAX_SLICES = 200


@dataclass(frozen=True)
class CycleConfig:
    """How the node turns files into a cycle."""

    box: Box | None = None
    slice_interval_s: float = 0.0  # 0: every valid time of the source
    grid_stride: int = 1
    max_slices: int = MAX_SLICES
    max_slice_bytes: int = MAX_SLICE_BYTES
    required: tuple[str, ...] = ()
    cycle_id: str = ""
    notes: list[str] = field(default_factory=list)
    waves_from_wind: bool = True  # estimate waves of a wind-only cycle (else refuse it)
    max_members: int = 0  # most members published (0: all); the rest dropped, stated
    member_labels: tuple[str, ...] = ()  # labels of multi-model members (default: sources)


def corridor_box(lat_deg: Sequence[float], lon_deg: Sequence[float], margin_deg: float) -> Box:
    """Bounding box of a route (longitudes unwrapped so it may cross 180) plus a margin."""
    lon = np.unwrap(np.asarray(lon_deg, dtype=np.float64) % 360.0, period=360.0)
    lat = np.asarray(lat_deg, dtype=np.float64)
    return Box(max(-90.0, float(lat.min()) - margin_deg), min(90.0, float(lat.max()) + margin_deg),
               float(lon.min()) - margin_deg, float(lon.max()) + margin_deg)


def thin(ds: xr.Dataset, cfg: CycleConfig) -> tuple[xr.Dataset, list[str]]:
    """Apply region, time interval, stride and the size/count bounds; notes say what changed."""
    notes: list[str] = []
    stride = max(1, cfg.grid_stride)
    if cfg.box is not None:
        ds = subset(ds, cfg.box)
    if cfg.slice_interval_s > 0 and ds.sizes["time"] > 1:
        t = ds["time"].values.astype("datetime64[ns]").astype(np.int64) / 1e9
        keep = [0]
        for i in range(1, t.size):
            if t[i] - t[keep[-1]] >= cfg.slice_interval_s - 1e-6:
                keep.append(i)
        ds = ds.isel(time=keep)
    n_fields = len(cv.present_variables(ds))
    while True:
        ny = -(-ds.sizes["latitude"] // stride)
        nx = -(-ds.sizes["longitude"] // stride)
        if ny * nx * 4 * n_fields <= cfg.max_slice_bytes or ny * nx <= 4:
            break
        stride += 1
    if stride > 1:
        ds = snap_grid(ds.isel(latitude=slice(None, None, stride),
                               longitude=slice(None, None, stride)))
        if stride != cfg.grid_stride:
            notes.append(f"grid thinned by {stride} to keep slices <= {cfg.max_slice_bytes} B")
    ds, member_notes = _member_budget(ds, cfg)
    notes += member_notes
    m = member_count(ds)
    if m > 1 and m * ds.sizes["time"] > cfg.max_slices:
        ds, note = _member_time_stride(ds, m, cfg.max_slices)
        notes.append(note)
    if ds.sizes["time"] > cfg.max_slices:
        notes.append(f"cycle cut to its first {cfg.max_slices} of {ds.sizes['time']} slices")
        ds = ds.isel(time=slice(0, cfg.max_slices))
    return ds, notes


def member_time_stride(members: int, n_times: int, max_slices: int) -> int:
    """Every k-th valid time of each member so that members x times <= max_slices: the whole
    horizon stays covered at a coarser step (a voyage outlives a forecast; cutting the horizon
    instead would leave the plan on persistence and calm water after a day or two)."""
    if members <= 1 or members * n_times <= max_slices:
        return 1
    return -(-n_times // max(1, max_slices // members))


def member_stride_note(members: int, n_times: int, max_slices: int, stride: int,
                       step_h: float) -> str:
    """What `member_time_stride` did, in words (the same for the whole and the streamed load)."""
    kept = len(range(0, n_times, stride))
    return (f"{members} members x {n_times} valid times exceed max_slices {max_slices}: "
            f"one valid time in {stride} kept ({kept} per member, {step_h:g} h apart, the "
            "whole horizon)")


def _member_time_stride(ds: xr.Dataset, members: int, max_slices: int
                        ) -> tuple[xr.Dataset, str]:
    """`member_time_stride` applied to a dataset, with its note."""
    n_t = ds.sizes["time"]
    stride = member_time_stride(members, n_t, max_slices)
    kept = ds.isel(time=slice(0, None, stride))
    t = kept["time"].values
    step_h = float((t[1] - t[0]) / np.timedelta64(1, "h")) if t.size > 1 else 0.0
    return kept, member_stride_note(members, n_t, max_slices, stride, step_h)


def _member_budget(ds: xr.Dataset, cfg: CycleConfig) -> tuple[xr.Dataset, list[str]]:
    """The first `cfg.max_members` members (the control and the first perturbed ones of an
    ensemble: members are exchangeable draws, so a prefix is an unbiased subset), stated."""
    m = member_count(ds)
    if cfg.max_members <= 0 or m <= cfg.max_members:
        return ds, []
    kept = ds.isel({MEMBER_DIM: slice(0, cfg.max_members)})
    kept = kept.assign_coords({MEMBER_DIM: np.arange(cfg.max_members, dtype=np.int64)})
    if cfg.max_members == 1:
        kept = select_member(kept, 0)
    labels = member_labels(ds)
    return kept, [f"{m - cfg.max_members} of {m} members dropped (max_members "
                  f"{cfg.max_members}): kept {', '.join(labels[:cfg.max_members])}"]


def build_cycle(paths: Sequence[str], cfg: CycleConfig,
                members: Sequence[Sequence[str]] = ()
                ) -> tuple[CycleInfo, list[SliceData], list[str]]:
    """Load + validate + thin files into the cycle announcement and its slices; with
    `members` (the files of each member) a multi-model cycle (`members.open_members`)."""
    if members:
        ds = open_members(members, cfg.member_labels, required=cfg.required,
                          cycle_id=cfg.cycle_id or None, waves_from_wind=cfg.waves_from_wind)
        paths = [str(f) for files in members for f in files]
    else:
        ds = open_forecast(list(paths), required=cfg.required, cycle_id=cfg.cycle_id or None,
                           waves_from_wind=cfg.waves_from_wind)
    report = load_notes(ds)
    ds, notes = thin(ds, cfg)
    if ds.sizes["time"] == 0:
        raise SliceError(f"{', '.join(paths)}: no valid time left after thinning")
    info = replace(cycle_info(ds, paths), notes=tuple(report + notes))
    return info, list(dataset_to_slices(ds)), report + notes
