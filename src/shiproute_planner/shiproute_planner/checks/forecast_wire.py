"""Checks of forecast slices as they arrive on the wire, before anything is allocated for them.

A slice declares its grid (origin, spacing, shape) and its cycle's slice count; the planner
sizes the cycle's sampler array from the first slice, so every declaration is checked against
the data actually received and against fixed bounds first (a slice declaring 10^6 x 10^6
cells must not make the planner try to allocate it). Values must be finite or NaN (missing),
within the canonical physical ranges; times within a sane window. Every error names the cycle,
the slice, the input and what is wrong (`ForecastCycleError`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol

import numpy as np
from shiproute_weather.contract.canonical import VARIABLES, Grid
from shiproute_weather.sampling.sampler import channel_count
from shiproute_weather.wire.packing import PackedField

from ..errors import ForecastCycleError, StaleForecastError

#: most slices of one cycle: the planner's transient-local slice queue holds 512
MAX_SLICES_PER_CYCLE = 512
#: most grid cells of one slice: 0.1 deg over a whole ocean basin (2,000 x 2,000); the weather
#: node thins slices to 4 MB of float32 (1,048,576 cells for one field)
MAX_CELLS_PER_SLICE = 4_000_000
#: most bytes of a cycle's half-precision sampler array (what the planner allocates)
MAX_CYCLE_STORAGE_BYTES = 2 * 2**30
#: valid and reference times must fall in this window [POSIX s]: 1990-01-01 .. 2100-01-01
#: (no forecast on the wire is older than satellite-era analyses; a 1970 stamp is a zero time)
EARLIEST_TIME_S = 631152000.0
LATEST_TIME_S = 4102444800.0
#: slack on the physical ranges for the 16-bit packing step and float32 rounding
_RANGE_SLACK = 1e-3
_PACKED_MISSING = 65535


@dataclass(frozen=True)
class SliceHeader:
    """What a slice declares about itself (the numbers checked before any allocation)."""

    cycle_id: str
    index: int
    count: int
    valid_time_s: float
    reference_time_s: float
    grid: Grid


def _where(h: SliceHeader) -> str:
    return f"forecast cycle {h.cycle_id!r} slice {h.index}"


def check_grid(grid: Grid, where: str) -> None:
    """Shape >= 2 x 2 (bilinear sampling), finite positive spacing, finite origin, latitudes
    within -90..90 and a bounded cell count."""
    if grid.n_lat < 2 or grid.n_lon < 2:
        raise ForecastCycleError(f"{where}: grid shape {grid.n_lat} x {grid.n_lon}; expected at "
                                 "least 2 x 2 (the sampler interpolates between nodes)")
    for name, step in (("dlat_deg", grid.dlat_deg), ("dlon_deg", grid.dlon_deg)):
        if not (math.isfinite(step) and step > 0.0):
            raise ForecastCycleError(f"{where}: {name} = {step!r}; expected a finite spacing "
                                     "> 0 (ascending coordinates)")
        if step > 45.0:
            raise ForecastCycleError(f"{where}: {name} = {step!r}; expected at most 45 deg")
    for name, value in (("lat0_deg", grid.lat0_deg), ("lon0_deg", grid.lon0_deg)):
        if not math.isfinite(value):
            raise ForecastCycleError(f"{where}: {name} = {value!r}; expected a finite value")
    cells = grid.n_lat * grid.n_lon
    if cells > MAX_CELLS_PER_SLICE:
        raise ForecastCycleError(f"{where}: grid {grid.n_lat} x {grid.n_lon} = {cells} cells; "
                                 f"expected at most {MAX_CELLS_PER_SLICE}")
    top = grid.lat0_deg + grid.dlat_deg * (grid.n_lat - 1)
    if grid.lat0_deg < -90.0 - 1e-9 or top > 90.0 + 1e-9:
        raise ForecastCycleError(f"{where}: latitudes {grid.lat0_deg:g}..{top:g}; expected "
                                 "within -90..90")
    if not -360.0 <= grid.lon0_deg <= 360.0 or grid.dlon_deg * (grid.n_lon - 1) > 360.0 + 1e-6:
        raise ForecastCycleError(f"{where}: longitudes from {grid.lon0_deg:g} spanning "
                                 f"{grid.dlon_deg * (grid.n_lon - 1):g} deg; expected a start "
                                 "within -360..360 and a span of at most 360 deg")


def check_time(name: str, value_s: float, where: str) -> None:
    """A POSIX time that is finite and inside 1990..2100."""
    if not (math.isfinite(value_s) and EARLIEST_TIME_S <= value_s <= LATEST_TIME_S):
        raise ForecastCycleError(f"{where}: {name} = {value_s!r} s; expected a UTC time "
                                 "between 1990-01-01 and 2100-01-01")


def check_slice_count(cycle_id: str, count: int) -> None:
    """A cycle's declared slice count: 1..MAX_SLICES_PER_CYCLE."""
    if not 1 <= count <= MAX_SLICES_PER_CYCLE:
        raise ForecastCycleError(f"forecast cycle {cycle_id!r}: slice_count = {count}; "
                                 f"expected 1..{MAX_SLICES_PER_CYCLE}")


def check_header(h: SliceHeader, n_channels: int, storage_itemsize: int = 2) -> None:
    """Everything a slice declares, before a byte is allocated for its cycle."""
    where = _where(h)
    if not h.cycle_id.strip():
        raise ForecastCycleError(f"{where}: cycle_id is empty")
    check_slice_count(h.cycle_id, h.count)
    if not 0 <= h.index < h.count:
        raise ForecastCycleError(f"{where}: slice_index {h.index} outside 0..{h.count - 1}")
    check_grid(h.grid, where)
    check_time("valid_time", h.valid_time_s, where)
    if h.reference_time_s != 0.0:  # 0: not stated (an unset Time)
        check_time("reference_time", h.reference_time_s, where)
    storage = h.count * h.grid.n_lat * h.grid.n_lon * max(n_channels, 1) * storage_itemsize
    if storage > MAX_CYCLE_STORAGE_BYTES:
        raise ForecastCycleError(
            f"{where}: {h.count} slices of {h.grid.n_lat} x {h.grid.n_lon} x {n_channels} "
            f"channels need {storage / 2**20:.0f} MiB; expected at most "
            f"{MAX_CYCLE_STORAGE_BYTES / 2**20:.0f} MiB")


def check_field(name: str, values: np.ndarray | PackedField, cells: int, where: str) -> None:
    """One field: a canonical name, exactly `cells` values, finite or NaN, within the
    variable's physical range (packed: from its scaling; float32: fmin/fmax, no copy)."""
    spec = VARIABLES.get(name)
    if spec is None:
        raise ForecastCycleError(f"{where}: field {name!r} is not a canonical variable")
    if values.size != cells:
        raise ForecastCycleError(f"{where}: field {name} has {values.size} values, expected "
                                 f"{cells} (n_lat x n_lon declared by the slice)")
    slack = _RANGE_SLACK * max(1.0, abs(spec.valid_min), abs(spec.valid_max))
    if isinstance(values, PackedField):
        off, scale = values.add_offset, values.scale_factor
        if not (math.isfinite(off) and math.isfinite(scale) and scale >= 0.0):
            raise ForecastCycleError(f"{where}: field {name} packing add_offset={off!r}, "
                                     f"scale_factor={scale!r}; expected finite, scale >= 0")
        codes = values.codes
        present = codes[codes != _PACKED_MISSING] if scale > 0 else codes[:0]
        if scale == 0.0 and off == 0.0:
            return  # all missing, or all zero
        lo = off
        hi = off + scale * float(present.max()) if present.size else off
    else:
        if values.size == 0:
            return
        lo = float(np.fmin.reduce(values, axis=None))
        hi = float(np.fmax.reduce(values, axis=None))
        if math.isnan(lo):
            return  # all missing
        if math.isinf(lo) or math.isinf(hi):
            raise ForecastCycleError(f"{where}: field {name} holds infinite values; expected "
                                     "finite values or NaN (missing)")
    if lo < spec.valid_min - slack or hi > spec.valid_max + slack:
        raise ForecastCycleError(f"{where}: field {name} spans {lo:.6g}..{hi:.6g} "
                                 f"{spec.units}; expected {spec.long_name} within "
                                 f"{spec.valid_min:g}..{spec.valid_max:g} {spec.units}")


def check_fields(h: SliceHeader, fields: tuple[tuple[str, object], ...]) -> None:
    """All fields of a slice: at least one, no name twice, each checked by `check_field`."""
    where = _where(h)
    if not fields:
        raise ForecastCycleError(f"{where}: no fields")
    names = [name for name, _ in fields]
    if len(set(names)) != len(names):
        raise ForecastCycleError(f"{where}: a field name appears twice in {names}")
    cells = h.grid.n_lat * h.grid.n_lon
    for name, values in fields:
        check_field(name, values, cells, where)  # type: ignore[arg-type]


def channels_of(fields: tuple[tuple[str, object], ...]) -> int:
    """Sampler channels the canonical fields of a slice take."""
    return channel_count(n for n, _ in fields if n in VARIABLES)


def check_not_older(cycle_id: str, reference_s: float, in_force_id: str,
                    in_force_reference_s: float) -> None:
    """Raise StaleForecastError when a cycle's model run is older than the one in force
    (a delayed or replayed cycle must not replace a newer forecast unless asked)."""
    if (math.isfinite(reference_s) and math.isfinite(in_force_reference_s)
            and reference_s > 0 and in_force_reference_s > 0
            and reference_s < in_force_reference_s):
        from datetime import UTC, datetime

        def iso(t: float) -> str:
            return datetime.fromtimestamp(t, UTC).strftime("%Y-%m-%dT%H:%MZ")

        raise StaleForecastError(
            f"forecast cycle {cycle_id!r}: reference time {iso(reference_s)} is older than "
            f"{iso(in_force_reference_s)} of cycle {in_force_id!r} in force (set parameter "
            "accept_older_forecasts to use it)")


class ReceivedSlice(Protocol):
    """What the slice checks read of a received slice (the intake's `SliceFields`)."""

    @property
    def cycle_id(self) -> str: ...
    @property
    def index(self) -> int: ...
    @property
    def count(self) -> int: ...
    @property
    def valid_time_s(self) -> float: ...
    @property
    def reference_time_s(self) -> float: ...
    @property
    def grid(self) -> Grid: ...
    @property
    def fields(self) -> tuple[tuple[str, object], ...]: ...
    @property
    def problems(self) -> tuple[str, ...]: ...


def check_slice_fields(s: ReceivedSlice) -> None:
    """Every check of one received slice (header, then fields), before it is assembled."""
    header = SliceHeader(s.cycle_id, s.index, s.count, s.valid_time_s, s.reference_time_s,
                         s.grid)
    check_header(header, channels_of(s.fields))
    if s.problems:
        raise ForecastCycleError(f"{_where(header)}: {'; '.join(s.problems)}")
    check_fields(header, s.fields)
