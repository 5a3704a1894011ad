"""Pack a forecast cycle into the sampler's array slice by slice, as the slices arrive.

The planner node keeps no copy of a cycle besides its sampler: each slice is written into the
(time, latitude, longitude, channel) array the moment it arrives (its message is then dropped),
so the sampler is ready when the last slice lands. Slices valid more than `KEEP_BEHIND_S`
before the ship's time are received but not stored: re-plans start at the ship's time, and the
pages of an array that are never written cost no memory. Storage is half precision by
default (see `shiproute_weather.sampling.sampler.STORAGE_DTYPES`); fields arrive as float32
or 16-bit packed codes and are decoded, turned into sine/cosine (directions) and rounded to
half in one numba pass per slice (`shiproute_weather.sampling.sampler.pack_fields`), without
the GIL.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from shiproute_weather.contract.canonical import CANONICAL_ORDER, Grid
from shiproute_weather.sampling.sampler import (
    FieldValues,
    ForecastSampler,
    channel_count,
    pack_fields,
)

from ..errors import ForecastCycleError

#: stored history behind the ship: longer than the time step of any forecast we load (1-6 h),
#: so the slice valid just before the ship's time is kept and sampling never clamps there
KEEP_BEHIND_S = 12 * 3600.0
HS_VAR = "sea_surface_wave_significant_height"


@dataclass(frozen=True)
class SliceFields:
    """One forecast slice as the packer needs it (a ROS-free view of a ForecastSlice)."""

    cycle_id: str
    index: int
    count: int
    valid_time_s: float  # POSIX seconds, UTC
    grid: Grid
    # (CF name, n_lat * n_lon values: float32, or 16-bit wire codes with their scaling)
    fields: tuple[tuple[str, FieldValues], ...]
    problems: tuple[str, ...] = ()  # malformed fields found while reading the message
    reference_time_s: float = 0.0  # forecast reference time (POSIX s); 0 = not stated
    publication_id: str = ""  # the publisher's publication of the cycle ('' = not stated)
    member: int = 0  # member of this slice (ForecastSlice.member)
    member_count: int = 1  # members of its cycle (1: deterministic)
    member_label: str = ""  # the member's label



def canonical_variables(first: SliceFields) -> list[str]:
    """The canonical fields a cycle's first slice carries, in canonical order (a slice
    without any is refused naming the cycle and what it had)."""
    present = {name for name, _ in first.fields}
    variables = [n for n in CANONICAL_ORDER if n in present]
    if not variables:
        raise ForecastCycleError(f"forecast cycle {first.cycle_id!r}: slice {first.index} "
                                 f"has no canonical field (got {sorted(present)})")
    return variables


class CyclePacker:
    """Collects the slices of one cycle into a `ForecastSampler` (a `CycleAssembler` sink).

    `add` may run in several threads at once for different slices (each writes its own part
    of the array; the heavy work runs without the GIL)."""

    def __init__(self, first: SliceFields, keep_from_s: Callable[[], float] = lambda: -math.inf,
                 dtype: Any = np.float16) -> None:
        self.cycle_id, self.count, self.grid = first.cycle_id, first.count, first.grid
        self.reference_time_s = first.reference_time_s
        self.variables = canonical_variables(first)
        self._names = [name for name, _ in first.fields]
        self._keep_from_s = keep_from_s
        g = self.grid
        # np.empty maps the pages lazily: slices never written cost no memory
        self._data = np.empty((self.count, g.n_lat, g.n_lon, channel_count(self.variables)),
                              dtype=dtype)
        self._times_s = np.full(self.count, np.nan)
        self._stored = np.zeros(self.count, dtype=bool)

    def add(self, index: int, s: SliceFields) -> None:
        """Check one slice against the cycle and write it into the array (unless too old)."""
        where = f"forecast cycle {self.cycle_id!r} slice {index}"
        if s.cycle_id != self.cycle_id or s.count != self.count:
            raise ForecastCycleError(f"{where}: belongs to {s.cycle_id!r} of {s.count} slices, "
                                     f"expected {self.count}")
        if s.member_count != 1 or s.member != 0:
            raise ForecastCycleError(f"{where}: member {s.member} of {s.member_count} in a "
                                     "cycle whose first slice is deterministic (member count "
                                     "mismatch)")
        if s.problems:
            raise ForecastCycleError(f"{where}: {'; '.join(s.problems)}")
        if s.reference_time_s != self.reference_time_s:
            raise ForecastCycleError(f"{where}: reference time {s.reference_time_s} differs from "
                                     f"{self.reference_time_s} of the cycle's first slice")
        if s.grid != self.grid:
            raise ForecastCycleError(f"{where}: grid {s.grid} differs from {self.grid}")
        if [name for name, _ in s.fields] != self._names:
            raise ForecastCycleError(f"{where}: fields {[n for n, _ in s.fields]} differ from "
                                     f"{self._names}")
        g = self.grid
        for name, values in s.fields:
            if values.size != g.n_lat * g.n_lon:
                raise ForecastCycleError(f"{where}: field {name} has {values.size} values, "
                                         f"expected {g.n_lat} x {g.n_lon}")
        if not math.isfinite(s.valid_time_s):
            raise ForecastCycleError(f"{where}: valid time {s.valid_time_s} is not finite")
        self._times_s[index] = s.valid_time_s
        if index == self.count - 1 or s.valid_time_s >= self._keep_from_s() - KEEP_BEHIND_S:
            pack_fields(self._data[index], self.variables, dict(s.fields).__getitem__)
            self._stored[index] = True

    def result(self) -> ForecastSampler:
        """The cycle's sampler over the stored run of slices up to the last one."""
        t = self._times_s
        if t.size > 1 and not np.all(np.diff(t) > 0):
            raise ForecastCycleError(f"forecast cycle {self.cycle_id!r}: valid times are not "
                                     "strictly ascending with the slice index")
        missing = np.flatnonzero(~self._stored)
        k0 = int(missing[-1]) + 1 if missing.size else 0
        sampler = ForecastSampler.from_packed(self._data[k0:], t[k0:], self.grid, self.variables)
        sampler.reference_time_s = self.reference_time_s  # the model run, for the staleness check
        return sampler


def hs_field_at(sampler: ForecastSampler, time_s: float) -> Any:
    """Total Hs on the sampler's grid at `time_s` as a one-time canonical Dataset (for the
    plan's PNG), or None when the forecast has no total Hs."""
    if HS_VAR not in sampler.variables:
        return None
    import xarray as xr

    g = sampler.grid
    lat, lon = g.latitudes_deg, g.longitudes_deg
    glat, glon = np.meshgrid(lat, lon, indexing="ij")
    hs = sampler.sample(glon, glat, np.full(glat.shape, float(time_s)))[HS_VAR]
    when = np.array([round(float(time_s) * 1e9)], dtype="datetime64[ns]")
    return xr.Dataset({HS_VAR: (("time", "latitude", "longitude"), hs[None].astype(np.float32))},
                      coords={"time": when, "latitude": lat, "longitude": lon})
