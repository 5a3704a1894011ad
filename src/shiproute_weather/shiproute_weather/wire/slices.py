"""ROS-free, lossless split of a canonical dataset into per-valid-time slices and back.

A slice holds float32 fields on a regular grid given by (lat0, dlat, n_lat, lon0, dlon, n_lon);
`convert.py` maps these one-to-one onto shiproute_msgs/ForecastSlice and ForecastCycle. The
canonical coordinates are exactly lat0 + i * dlat (see `snap_grid`) so the round trip
dataset -> slices -> dataset reproduces data, grid, times and attrs bit for bit.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass

import numpy as np
import xarray as xr

from ..contract import canonical as cv
from ..contract.members import (
    MEMBER_DIM,
    MEMBER_LABEL,
    check_unique_labels,
    member_count,
    member_labels,
)
from ..contract.timefmt import iso_to_ns, ns_to_iso
from ..errors import SliceError
from .packing import PackedField, unpack_field


@dataclass(frozen=True)
class SliceGrid:
    """Regular grid of a slice: node (i, j) at (lat0 + i dlat, lon0 + j dlon)."""

    lat0_deg: float
    lon0_deg: float
    dlat_deg: float
    dlon_deg: float
    n_lat: int
    n_lon: int


@dataclass(frozen=True)
class FieldData:
    """One named field: n_lat * n_lon values, row-major (latitude rows): float32, or 16-bit
    wire codes (`PackedField`, only as read in place from a message)."""

    name: str
    units: str
    direction_convention: str
    data: np.ndarray | PackedField


@dataclass(frozen=True)
class SliceData:
    """One valid time of a forecast cycle."""

    cycle_id: str
    reference_time_ns: int
    valid_time_ns: int
    slice_index: int
    slice_count: int
    source: str
    grid: SliceGrid
    fields: tuple[FieldData, ...]
    member: int = 0  # 0..member_count-1; slice_index = member * times per member + time
    member_count: int = 1  # 1: a deterministic cycle
    member_label: str = ""  # the member's label (ensemble number or model), '' when one

    @property
    def nbytes(self) -> int:
        """Bytes of field data carried by the slice (as held: float32 or 16-bit codes)."""
        return sum(f.data.nbytes for f in self.fields)


@dataclass(frozen=True)
class CycleInfo:
    """Announcement of a complete cycle (ForecastCycle)."""

    cycle_id: str
    reference_time_ns: int
    first_valid_time_ns: int
    last_valid_time_ns: int
    step_s: float
    slice_count: int
    source: str
    lat_min_deg: float
    lat_max_deg: float
    lon_min_deg: float
    lon_max_deg: float
    fields: tuple[str, ...]
    source_files: tuple[str, ...]
    field_sources: tuple[str, ...] = ()  # source file of each entry of `fields`
    notes: tuple[str, ...] = ()  # what the load estimated, converted, masked or lacks
    member_count: int = 1  # members of the cycle; slice_count = member_count x valid times
    member_labels: tuple[str, ...] = ()  # label of each member ('' for a deterministic one)
    member_kind: str = ""  # "ensemble" | "multi-model" ('' deterministic)


def _step(first: float, last: float, n: int) -> float:
    return float(f"{(last - first) / (n - 1):.10g}") if n > 1 else 1.0


def snap_grid(ds: xr.Dataset) -> xr.Dataset:
    """Set latitude/longitude to exactly first + i * step (step rounded to 10 digits)."""
    coords = {}
    for name in ("latitude", "longitude"):
        v = ds[name].values.astype(np.float64)
        first = float(f"{v[0]:.10g}")
        coords[name] = first + _step(v[0], v[-1], v.size) * np.arange(v.size)
    if all(np.array_equal(coords[n], ds[n].values) for n in coords):
        return ds
    return ds.assign_coords(coords)


def slice_grid(ds: xr.Dataset) -> SliceGrid:
    """Grid of a (snapped) canonical dataset."""
    lat = ds["latitude"].values
    lon = ds["longitude"].values
    return SliceGrid(float(lat[0]), float(lon[0]), _step(lat[0], lat[-1], lat.size),
                     _step(lon[0], lon[-1], lon.size), int(lat.size), int(lon.size))


def cycle_info(ds: xr.Dataset, source_files: Sequence[str] = ()) -> CycleInfo:
    """ForecastCycle content for a canonical dataset (slice_count counts every member's)."""
    t = ds["time"].values.astype("datetime64[ns]").astype(np.int64)
    lat, lon = ds["latitude"].values, ds["longitude"].values
    step = float((t[1] - t[0]) / 1e9) if t.size > 1 else 0.0
    m = member_count(ds)
    return CycleInfo(str(ds.attrs["cycle_id"]), iso_to_ns(ds.attrs["forecast_reference_time"]),
                     int(t[0]), int(t[-1]), step, m * int(t.size), str(ds.attrs["source"]),
                     float(lat[0]), float(lat[-1]), float(lon[0]), float(lon[-1]),
                     tuple(cv.present_variables(ds)), tuple(str(f) for f in source_files),
                     tuple(str(ds[n].attrs.get("source_file", "")) for n in
                           cv.present_variables(ds)),
                     member_count=m,
                     member_labels=member_labels(ds) if MEMBER_DIM in ds.dims else (),
                     member_kind=str(ds.attrs.get("member_kind", "")) if m > 1 else "")


def dataset_to_slices(ds: xr.Dataset) -> Iterator[SliceData]:
    """Yield one SliceData per member and valid time, member by member (fields in canonical
    order, float32 copies); slice_index = member x valid times + time index."""
    grid = slice_grid(ds)
    names = cv.present_variables(ds)
    has_members = MEMBER_DIM in ds.dims
    dims = ((MEMBER_DIM,) if has_members else ()) + ("time", "latitude", "longitude")
    arrays = {n: ds.variables[n].transpose(*dims).values for n in names}
    if not has_members:
        arrays = {n: a[None] for n, a in arrays.items()}
    labels = member_labels(ds) if has_members else ("",)
    times = ds["time"].values.astype("datetime64[ns]").astype(np.int64)
    ref = iso_to_ns(ds.attrs["forecast_reference_time"])
    n_t, n_m = int(times.size), len(labels)
    for m, label in enumerate(labels):
        for k, t in enumerate(times):
            fields = tuple(
                FieldData(n, cv.VARIABLES[n].units, cv.VARIABLES[n].direction_convention,
                          np.ascontiguousarray(arrays[n][m, k], dtype=np.float32).reshape(-1))
                for n in names)
            yield SliceData(str(ds.attrs["cycle_id"]), ref, int(t), m * n_t + k, n_m * n_t,
                            str(ds.attrs["source"]), grid, fields, m, n_m, label)


def _member_runs(ordered: Sequence[SliceData]) -> tuple[int, int, list[str]]:
    """(members, valid times per member, labels) of a cycle's ordered slices; raises
    SliceError when the slices disagree on the member count or a member's label."""
    first = ordered[0]
    n_m = first.member_count
    if n_m < 1 or first.slice_count % n_m:
        raise SliceError(f"cycle {first.cycle_id}: {first.slice_count} slices cannot be split "
                         f"into {n_m} members")
    n_t = first.slice_count // n_m
    labels: list[str | None] = [None] * n_m
    for s in ordered:
        if s.member_count != n_m:
            raise SliceError(f"cycle {first.cycle_id}: slice {s.slice_index} says "
                             f"{s.member_count} members, slice {first.slice_index} says {n_m} "
                             "(member count mismatch)")
        if s.member != s.slice_index // n_t:
            raise SliceError(f"cycle {first.cycle_id}: slice {s.slice_index} is member "
                             f"{s.member}, expected {s.slice_index // n_t} ({n_t} valid times "
                             "per member)")
        if labels[s.member] is None:
            labels[s.member] = s.member_label
        elif labels[s.member] != s.member_label:
            raise SliceError(f"cycle {first.cycle_id}: member {s.member} labelled "
                             f"{labels[s.member]!r} and {s.member_label!r}")
    names = [str(x) for x in labels]
    if n_m > 1:
        check_unique_labels(names, f"cycle {first.cycle_id}")
    return n_m, n_t, names


def slices_to_dataset(slices: Sequence[SliceData], member_kind: str = "ensemble") -> xr.Dataset:
    """Rebuild the canonical dataset of a complete cycle (with its member dimension and
    `member_kind`, from the cycle's announcement, when it has several members); raises
    SliceError if inconsistent."""
    if not slices:
        raise SliceError("no slices to assemble")
    ordered = sorted(slices, key=lambda s: s.slice_index)
    first = ordered[0]
    count = first.slice_count
    if [s.slice_index for s in ordered] != list(range(count)):
        raise SliceError(f"cycle {first.cycle_id}: have slice indices "
                         f"{[s.slice_index for s in ordered][:10]}..., expected 0..{count - 1}")
    n_m, n_t, labels = _member_runs(ordered)
    g = first.grid
    names = [f.name for f in first.fields]
    data = {n: np.empty((n_m, n_t, g.n_lat, g.n_lon), dtype=np.float32) for n in names}
    for s in ordered:
        if s.cycle_id != first.cycle_id or s.grid != g or [f.name for f in s.fields] != names:
            raise SliceError(f"slice {s.slice_index} of {s.cycle_id} does not match cycle "
                             f"{first.cycle_id} (grid or fields differ)")
        k = s.slice_index - s.member * n_t
        for f in s.fields:
            if f.data.size != g.n_lat * g.n_lon:
                raise SliceError(f"slice {s.slice_index} field {f.name}: {f.data.size} values, "
                                 f"expected {g.n_lat} x {g.n_lon}")
            if isinstance(f.data, PackedField):  # decoded straight into the dataset
                unpack_field(f.data, out=data[f.name][s.member, k].reshape(-1))
            else:
                data[f.name][s.member, k] = f.data.reshape(g.n_lat, g.n_lon)
    times = np.array([s.valid_time_ns for s in ordered[:n_t]],
                     dtype=np.int64).astype("datetime64[ns]")
    for s in ordered[n_t:]:
        if s.valid_time_ns != ordered[s.slice_index - s.member * n_t].valid_time_ns:
            raise SliceError(f"cycle {first.cycle_id}: slice {s.slice_index} (member "
                             f"{s.member}) has another valid time than member 0's")
    dims: tuple[str, ...] = ("time", "latitude", "longitude")
    coords: dict[str, object] = {
        "time": times, "latitude": g.lat0_deg + g.dlat_deg * np.arange(g.n_lat),
        "longitude": g.lon0_deg + g.dlon_deg * np.arange(g.n_lon)}
    if n_m > 1:
        dims = (MEMBER_DIM, *dims)
        coords[MEMBER_DIM] = np.arange(n_m, dtype=np.int64)
        coords[MEMBER_LABEL] = (MEMBER_DIM, np.array(labels, dtype=object))
    ds = xr.Dataset(
        {n: (dims, data[n] if n_m > 1 else data[n][0]) for n in names}, coords=coords,
        attrs={"forecast_reference_time": ns_to_iso(first.reference_time_ns),
               "source": first.source, "cycle_id": first.cycle_id})
    if n_m > 1:
        ds.attrs["member_kind"] = member_kind
    return cv.annotate(ds)
