"""Assemble an ensemble (or multi-model) forecast cycle from its member slices, as they arrive.

A cycle of M members and T valid times arrives as M x T slices (`ForecastSlice.member`,
`slice_index = member x T + t`). Each slice is decoded on arrival into float32 arrays of shape
(member, time, latitude, longitude) (pages never written cost no memory); when every member's
slices are in, the cycle becomes a canonical dataset with a `member` dimension
(`shiproute_weather.contract.members`), which the plan call hands to `plan_voyage`. A slice
that disagrees with the cycle (member count, member index, label, grid, fields, times) fails
the whole cycle with the reason; a cycle missing any member's slice is never completed.
"""

from __future__ import annotations

import math
from datetime import UTC, datetime
from typing import Any

import numpy as np
from shiproute_weather.contract.canonical import annotate
from shiproute_weather.contract.members import MEMBER_DIM, MEMBER_LABEL
from shiproute_weather.wire.packing import PackedField, unpack_field

from ..checks.forecast_wire import MAX_CYCLE_STORAGE_BYTES
from ..errors import ForecastCycleError
from .cycle_packer import HS_VAR, SliceFields, canonical_variables


class EnsembleCycle:
    """A complete member cycle: the canonical dataset with its member dimension, and what the
    node reads of a cycle in force (reference time, valid times, bytes, record)."""

    def __init__(self, dataset: Any, reference_time_s: float) -> None:
        self.dataset = dataset
        self.reference_time_s = reference_time_s
        self.times_s = dataset["time"].values.astype("datetime64[ns]").astype(np.int64) / 1e9
        self.nbytes = int(sum(dataset[n].nbytes for n in dataset.data_vars))
        self.member_count = int(dataset.sizes[MEMBER_DIM])
        self.member_labels = tuple(str(x) for x in dataset[MEMBER_LABEL].values)
        self.record: dict[str, Any] | None = None

    def set_kind(self, kind: str) -> None:
        """The cycle announcement's member kind ('ensemble' or 'multi-model')."""
        self.dataset.attrs["member_kind"] = kind or "ensemble"


class MemberCyclePacker:
    """A `CycleAssembler` sink for a cycle of several members (see the module docstring)."""

    def __init__(self, first: SliceFields) -> None:
        self.cycle_id, self.count, self.grid = first.cycle_id, first.count, first.grid
        self.reference_time_s = first.reference_time_s
        self.members = first.member_count
        where = f"forecast cycle {first.cycle_id!r}"
        if self.members < 2 or self.count % self.members:
            raise ForecastCycleError(f"{where}: {self.count} slices cannot hold "
                                     f"{self.members} members of equal length")
        self.times = self.count // self.members
        self.variables = canonical_variables(first)
        self._names = [name for name, _ in first.fields]
        g = self.grid
        need = self.count * g.n_lat * g.n_lon * len(self.variables) * 4
        if need > MAX_CYCLE_STORAGE_BYTES:
            raise ForecastCycleError(
                f"{where}: {self.members} members x {self.times} slices of {g.n_lat} x "
                f"{g.n_lon} x {len(self.variables)} fields need {need / 2**20:.0f} MiB; expected "
                f"at most {MAX_CYCLE_STORAGE_BYTES / 2**20:.0f} MiB")
        shape = (self.members, self.times, g.n_lat, g.n_lon)
        self._data = {n: np.empty(shape, dtype=np.float32) for n in self.variables}
        self._times_s = np.full((self.members, self.times), np.nan)
        self._labels: list[str | None] = [None] * self.members

    def add(self, index: int, s: SliceFields) -> None:
        """Check one member slice against the cycle and decode it into the arrays."""
        where = f"forecast cycle {self.cycle_id!r} slice {index}"
        if s.cycle_id != self.cycle_id or s.count != self.count:
            raise ForecastCycleError(f"{where}: belongs to {s.cycle_id!r} of {s.count} slices, "
                                     f"expected {self.count}")
        if s.member_count != self.members:
            raise ForecastCycleError(f"{where}: member_count {s.member_count} differs from "
                                     f"{self.members} of the cycle's first slice (member count "
                                     "mismatch)")
        if s.member != index // self.times:
            raise ForecastCycleError(f"{where}: member {s.member}, expected "
                                     f"{index // self.times} ({self.times} valid times per "
                                     "member)")
        known = self._labels[s.member]
        if known is not None and known != s.member_label:
            raise ForecastCycleError(f"{where}: member {s.member} labelled {s.member_label!r}, "
                                     f"earlier {known!r}")
        if s.member_label in [x for k, x in enumerate(self._labels) if k != s.member]:
            raise ForecastCycleError(f"{where}: member label {s.member_label!r} is already "
                                     "another member's (labels must be unique)")
        if s.problems:
            raise ForecastCycleError(f"{where}: {'; '.join(s.problems)}")
        if s.reference_time_s != self.reference_time_s or s.grid != self.grid:
            raise ForecastCycleError(f"{where}: reference time or grid differs from the "
                                     "cycle's first slice")
        if [name for name, _ in s.fields] != self._names:
            raise ForecastCycleError(f"{where}: fields {[n for n, _ in s.fields]} differ from "
                                     f"{self._names}")
        if not math.isfinite(s.valid_time_s):
            raise ForecastCycleError(f"{where}: valid time {s.valid_time_s} is not finite")
        g = self.grid
        m, k = s.member, index % self.times
        for name, values in s.fields:
            if name not in self._data:
                continue
            if values.size != g.n_lat * g.n_lon:
                raise ForecastCycleError(f"{where}: field {name} has {values.size} values, "
                                         f"expected {g.n_lat} x {g.n_lon}")
            out = self._data[name][m, k].reshape(-1)
            if isinstance(values, PackedField):
                unpack_field(values, out=out)
            else:
                out[:] = values
        self._labels[m] = s.member_label
        self._times_s[m, k] = s.valid_time_s

    def result(self) -> EnsembleCycle:
        """The complete cycle as a canonical dataset with its member dimension."""
        import xarray as xr

        t = self._times_s
        where = f"forecast cycle {self.cycle_id!r}"
        if self.times > 1 and not np.all(np.diff(t, axis=1) > 0):
            raise ForecastCycleError(f"{where}: valid times are not strictly ascending with "
                                     "the slice index within each member")
        if not np.all(t == t[:1]):
            raise ForecastCycleError(f"{where}: the members' valid times differ")
        g = self.grid
        ref = datetime.fromtimestamp(self.reference_time_s, UTC).strftime("%Y-%m-%dT%H:%M:%SZ")
        labels = [str(x) for x in self._labels]
        ds = xr.Dataset(
            {n: ((MEMBER_DIM, "time", "latitude", "longitude"), a)
             for n, a in self._data.items()},
            coords={MEMBER_DIM: np.arange(self.members, dtype=np.int64),
                    MEMBER_LABEL: (MEMBER_DIM, np.array(labels, dtype=object)),
                    "time": np.round(t[0] * 1e9).astype(np.int64).astype("datetime64[ns]"),
                    "latitude": g.latitudes_deg, "longitude": g.longitudes_deg},
            attrs={"forecast_reference_time": ref, "source": f"forecast cycle {self.cycle_id}",
                   "cycle_id": self.cycle_id, "member_kind": "ensemble"})
        return EnsembleCycle(annotate(ds), self.reference_time_s)


def ensemble_hs_field_at(cycle: EnsembleCycle, time_s: float) -> Any:
    """Member-mean total Hs at the valid time nearest `time_s` (for the plan's PNG), or None
    when the cycle has no total Hs."""
    ds = cycle.dataset
    if HS_VAR not in ds:
        return None
    k = int(np.argmin(np.abs(cycle.times_s - float(time_s))))
    mean = ds[HS_VAR].isel(time=[k]).mean(MEMBER_DIM, skipna=True).astype(np.float32)
    return mean.to_dataset(name=HS_VAR).drop_vars(MEMBER_LABEL, errors="ignore")
