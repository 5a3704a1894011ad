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
    """ForecastCycle content for a canonical dataset."""
    t = ds["time"].values.astype("datetime64[ns]").astype(np.int64)
    lat, lon = ds["latitude"].values, ds["longitude"].values
    step = float((t[1] - t[0]) / 1e9) if t.size > 1 else 0.0
    return CycleInfo(str(ds.attrs["cycle_id"]), iso_to_ns(ds.attrs["forecast_reference_time"]),
                     int(t[0]), int(t[-1]), step, int(t.size), str(ds.attrs["source"]),
                     float(lat[0]), float(lat[-1]), float(lon[0]), float(lon[-1]),
                     tuple(cv.present_variables(ds)), tuple(str(f) for f in source_files),
                     tuple(str(ds[n].attrs.get("source_file", "")) for n in
                           cv.present_variables(ds)))


def dataset_to_slices(ds: xr.Dataset) -> Iterator[SliceData]:
    """Yield one SliceData per valid time (fields in canonical order, float32 copies)."""
    grid = slice_grid(ds)
    names = cv.present_variables(ds)
    arrays = {n: ds.variables[n].transpose("time", "latitude", "longitude").values
              for n in names}
    times = ds["time"].values.astype("datetime64[ns]").astype(np.int64)
    ref = iso_to_ns(ds.attrs["forecast_reference_time"])
    for k, t in enumerate(times):
        fields = tuple(
            FieldData(n, cv.VARIABLES[n].units, cv.VARIABLES[n].direction_convention,
                      np.ascontiguousarray(arrays[n][k], dtype=np.float32).reshape(-1))
            for n in names)
        yield SliceData(str(ds.attrs["cycle_id"]), ref, int(t), k, int(times.size),
                        str(ds.attrs["source"]), grid, fields)


def slices_to_dataset(slices: Sequence[SliceData]) -> xr.Dataset:
    """Rebuild the canonical dataset of a complete cycle; raises SliceError if inconsistent."""
    if not slices:
        raise SliceError("no slices to assemble")
    ordered = sorted(slices, key=lambda s: s.slice_index)
    first = ordered[0]
    count = first.slice_count
    if [s.slice_index for s in ordered] != list(range(count)):
        raise SliceError(f"cycle {first.cycle_id}: have slice indices "
                         f"{[s.slice_index for s in ordered][:10]}..., expected 0..{count - 1}")
    g = first.grid
    names = [f.name for f in first.fields]
    data = {n: np.empty((count, g.n_lat, g.n_lon), dtype=np.float32) for n in names}
    for s in ordered:
        if s.cycle_id != first.cycle_id or s.grid != g or [f.name for f in s.fields] != names:
            raise SliceError(f"slice {s.slice_index} of {s.cycle_id} does not match cycle "
                             f"{first.cycle_id} (grid or fields differ)")
        for f in s.fields:
            if f.data.size != g.n_lat * g.n_lon:
                raise SliceError(f"slice {s.slice_index} field {f.name}: {f.data.size} values, "
                                 f"expected {g.n_lat} x {g.n_lon}")
            if isinstance(f.data, PackedField):  # decoded straight into the dataset
                unpack_field(f.data, out=data[f.name][s.slice_index].reshape(-1))
            else:
                data[f.name][s.slice_index] = f.data.reshape(g.n_lat, g.n_lon)
    times = np.array([s.valid_time_ns for s in ordered], dtype=np.int64).astype("datetime64[ns]")
    ds = xr.Dataset(
        {n: (("time", "latitude", "longitude"), data[n]) for n in names},
        coords={"time": times,
                "latitude": g.lat0_deg + g.dlat_deg * np.arange(g.n_lat),
                "longitude": g.lon0_deg + g.dlon_deg * np.arange(g.n_lon)},
        attrs={"forecast_reference_time": ns_to_iso(first.reference_time_ns),
               "source": first.source, "cycle_id": first.cycle_id})
    return cv.annotate(ds)
