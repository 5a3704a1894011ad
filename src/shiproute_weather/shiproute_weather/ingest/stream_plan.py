"""Which members and valid times of a (lazily opened) NetCDF file a streamed cycle publishes.

Decided from names, coordinates and sizes only, before any data is read, with the same budget
and words as `cycle_builder.thin`: the first `max_members` members, every k-th valid time when
members x times exceed `max_slices`, the first `max_slices` valid times of a deterministic file.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from .cycle_builder import CycleConfig, member_stride_note, member_time_stride
from .normalise import member_axis


@dataclass(frozen=True)
class StreamPlan:
    """The raw member indices and time indices to read, and what was left out (stated)."""

    member_dim: str  # the raw file's member dimension ('' for a deterministic file)
    members: tuple[int, ...]  # raw member indices read, in order (() deterministic)
    labels: tuple[str, ...]  # their labels (() deterministic or a single member kept)
    times: tuple[int, ...]  # raw time indices read for every member
    notes: tuple[str, ...]  # the budget's cuts, in words
    ensemble_note: str = ""  # the members kept (as `to_canonical` states it)

    @property
    def member_count(self) -> int:
        """Members published (1: deterministic)."""
        return max(1, len(self.labels))

    @property
    def slice_count(self) -> int:
        """Slices of the cycle: members x valid times."""
        return self.member_count * len(self.times)


def plan_stream(lazy: xr.Dataset, where: str, cfg: CycleConfig) -> StreamPlan:
    """The members and valid times of `lazy` (coordinates renamed, nothing read) to publish."""
    n_t = int(lazy.sizes["time"])
    dim, labels = member_axis(lazy, where)
    notes: list[str] = []
    members = list(range(len(labels)))
    if labels and 0 < cfg.max_members < len(labels):
        notes.append(f"{len(labels) - cfg.max_members} of {len(labels)} members dropped "
                     f"(max_members {cfg.max_members}): kept "
                     f"{', '.join(labels[:cfg.max_members])}")
        members = members[:cfg.max_members]
    kept_labels = [labels[k] for k in members]
    m = len(kept_labels)
    said = ""
    if len(labels) > 1:  # what the file holds, as the whole load states it before any cut
        said = (f"{len(labels)} members kept from dimension {dim!r} (labels "
                f"{', '.join(labels[:8])}{', ...' if len(labels) > 8 else ''})")
    stride = member_time_stride(max(1, m), n_t, cfg.max_slices)
    times = list(range(0, n_t, stride))
    if stride > 1:
        t = lazy["time"].values
        step_h = _hours(t[times[1]] - t[times[0]]) if len(times) > 1 else 0.0
        notes.append(member_stride_note(m, n_t, cfg.max_slices, stride, step_h))
    if len(times) > cfg.max_slices:
        notes.append(f"cycle cut to its first {cfg.max_slices} of {len(times)} slices")
        times = times[:cfg.max_slices]
    if m <= 1:  # one member kept: a deterministic cycle (like `members.select_member`)
        kept_labels = []
    return StreamPlan(dim, tuple(members), tuple(kept_labels), tuple(times), tuple(notes),
                      said)


def _hours(dt: object) -> float:
    """Hours of a time difference (a timedelta64, or a number of the file's raw time unit)."""
    if isinstance(dt, np.timedelta64):
        return float(dt / np.timedelta64(1, "h"))
    return float(dt)  # type: ignore[arg-type]
