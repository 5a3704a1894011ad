"""Vectorised sampling of a canonical forecast at arbitrary (longitude, latitude, time) points."""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from ..contract.canonical import (
    DIRECTION_VARIABLES,
    Grid,
    grid_of,
    present_variables,
    times_posix_s,
)
from ..errors import MissingVariableError
from ..wire.packing import PackedField, unpack_field
from .interp_kernel import MIN_VALID_WEIGHT, trilinear
from .pack_kernel import (
    CODES_DIRECTION,
    CODES_SCALAR,
    F32_DIRECTION,
    F32_SCALAR,
    address,
    pack_half_channels,
)

if TYPE_CHECKING:  # xarray is only needed by whoever passes a Dataset
    import xarray as xr

    from .members import MemberFields

__all__ = ["MIN_VALID_WEIGHT", "STORAGE_DTYPES", "FieldValues", "ForecastSampler",
           "channel_count", "pack_fields"]

#: one field as `pack_fields` takes it: float32 values, or 16-bit wire codes with their scaling
FieldValues = np.ndarray | PackedField

#: dtypes the sampler can keep its fields in: float32 (default) or IEEE half precision, whose
#: relative rounding (2^-11) is below the packing precision of the forecast sources themselves
STORAGE_DTYPES = (np.dtype(np.float32), np.dtype(np.float16))


def channel_count(variables: Iterable[str]) -> int:
    """Channels of the packed array: one per scalar, two (sine, cosine) per direction."""
    return sum(2 if n in DIRECTION_VARIABLES else 1 for n in variables)


def pack_fields(out: np.ndarray, variables: Sequence[str],
                values_of: Callable[[str], FieldValues]) -> None:
    """Fill `out` (..., channel) with the fields `values_of(name)`: float32 values or a
    `PackedField` of 16-bit wire codes, out.shape[:-1] values each (in C order, any shape);
    scalars as they are, directions [deg] as the sine and cosine of the angle.

    A float16 `out` is written by one fused numba kernel (`sampling.pack_kernel.pack_half_channels`:
    decode, sine/cosine and half rounding in a single blocked pass; the planner runs this for
    every slice of every cycle it receives); float32 `out` through numpy."""
    if out.dtype == np.float16:
        if not out.flags.c_contiguous:  # reshape would copy and the writes would be lost
            raise ValueError("pack_fields needs a C-contiguous float16 output array")
        _pack_half(out.reshape(-1, out.shape[-1]).view(np.uint16), variables, values_of)
        return
    c = 0
    for n in variables:
        values = values_of(n)
        values = (unpack_field(values) if isinstance(values, PackedField)
                  else np.asarray(values)).reshape(out.shape[:-1])
        if n in DIRECTION_VARIABLES:
            rad = np.deg2rad(np.asarray(values, dtype=np.float32))
            out[..., c], out[..., c + 1] = np.sin(rad), np.cos(rad)
            c += 2
        else:
            out[..., c] = values
            c += 1


def _pack_half(dst: np.ndarray, variables: Sequence[str],
               values_of: Callable[[str], FieldValues]) -> None:
    """Hand every field to `pack_half_channels` without copying (float32 values and wire
    codes are read in place; `keep` holds them alive while the kernel reads their memory)."""
    n_fields = len(variables)
    keep: list[np.ndarray] = []
    addresses = np.empty(n_fields, dtype=np.int64)
    kinds = np.empty(n_fields, dtype=np.int64)
    offsets = np.zeros(n_fields)
    scales = np.zeros(n_fields)
    for k, name in enumerate(variables):
        v = values_of(name)
        direction = name in DIRECTION_VARIABLES
        if isinstance(v, PackedField):
            flat = _flat(v.codes, np.uint16, dst.shape[0], name)
            offsets[k], scales[k] = v.add_offset, v.scale_factor
            kinds[k] = CODES_DIRECTION if direction else CODES_SCALAR
        else:
            flat = _flat(v, np.float32, dst.shape[0], name)
            kinds[k] = F32_DIRECTION if direction else F32_SCALAR
        keep.append(flat)
        addresses[k] = address(flat)
    if dst.shape[0]:
        pack_half_channels(addresses, kinds, offsets, scales, dst)
    del keep


def _flat(a: np.ndarray, dtype: type, size: int, name: str) -> np.ndarray:
    """C-contiguous flat array of `dtype` (a view when it already is one) of `size` values."""
    flat: np.ndarray = np.ascontiguousarray(a, dtype=dtype).reshape(-1)
    if flat.size != size:
        raise ValueError(f"field {name!r} has {flat.size} values, expected {size}")
    return flat


class ForecastSampler:
    """Trilinear interpolation in (time, latitude, longitude) of a canonical dataset.

    Longitudes are wrapped into the grid's range (and across the seam of a global grid);
    times outside the grid are clamped to its first/last valid time (without limit: planning
    uses `coverage.bounded_in_time`, which bounds that persistence and states it); points
    outside the latitude range or outside a regional longitude range give NaN. NaN nodes (e.g.
    land in a wave model) are skipped and the remaining weights renormalised when they carry at
    least `MIN_VALID_WEIGHT` of the total, else the result is NaN. Directions are interpolated as
    unit vectors (so 350 and 10 deg average to 0, not 180).

    The fields are copied once into a (time, lat, lon, channel) array (float32, or float16
    with `dtype=np.float16` at half the memory) so each sample reads its 8 corners from
    contiguous memory; `sample` runs a parallel numba kernel. `from_packed` wraps an array
    packed elsewhere (e.g. slice by slice as a cycle arrives) without another copy.
    """

    #: the ensemble's members when the dataset has a `member` dimension (`sample` and
    #: `kernel_data` then give their weighted mean), else None
    members: MemberFields | None

    #: what the cycle holds and where each field came from (`record.cycle_record`), or None
    #: when the sampler was packed from elsewhere without one
    record: dict[str, Any] | None
    #: reference time of the model run [POSIX s] (0.0: not stated), set by whoever packs a cycle
    reference_time_s: float = 0.0
    #: source of the climatology a time-bounded sampler falls back to ('' for none)
    climatology: str = ""

    def __init__(self, ds: xr.Dataset, variables: Iterable[str] | None = None,
                 dtype: np.dtype | type = np.float32,
                 member_dtype: np.dtype | type = np.float16) -> None:
        names = present_variables(ds) if variables is None else list(variables)
        for n in names:
            if n not in ds.data_vars:
                raise MissingVariableError(ds.attrs.get("cycle_id", "dataset"), n,
                                           "a variable present in the forecast dataset")
        grid = grid_of(ds)
        times_s = times_posix_s(ds)
        shape = (times_s.size, grid.n_lat, grid.n_lon, channel_count(names))
        members = None
        if "member" in ds.dims:  # ensemble: the weighted member mean is the one-forecast view
            from .members import pack_members

            data, members = pack_members(ds, names, shape, _storage_dtype(dtype),
                                         _storage_dtype(member_dtype), pack_fields)
        else:
            data = np.empty(shape, dtype=_storage_dtype(dtype))
            pack_fields(data, names, lambda n: ds[n].transpose("time", "latitude",
                                                               "longitude").values)
        self._init(data, times_s, grid, names)
        self.members = members
        from ..contract.record import cycle_record

        self.record = cycle_record(ds)

    @classmethod
    def from_packed(cls, data: np.ndarray, times_s: np.ndarray, grid: Grid,
                    variables: Sequence[str]) -> ForecastSampler:
        """Sampler over an array already packed by `pack_fields` (not copied)."""
        _storage_dtype(data.dtype)
        want = (np.asarray(times_s).size, grid.n_lat, grid.n_lon, channel_count(variables))
        if data.ndim != 4 or data.shape != want:
            raise ValueError(f"packed forecast array has shape {data.shape}, expected {want} "
                             "(time, latitude, longitude, channel)")
        obj = cls.__new__(cls)
        obj._init(data, np.asarray(times_s, dtype=np.float64), grid, list(variables))
        return obj

    def _init(self, data: np.ndarray, times_s: np.ndarray, grid: Grid,
              names: list[str]) -> None:
        self.variables: tuple[str, ...] = tuple(names)
        self.record = None
        #: every ensemble member stacked (`sampling.members`), None for one forecast
        self.members: MemberFields | None = None
        self.grid = grid
        self.times_s = np.ascontiguousarray(times_s, dtype=np.float64)
        if self.times_s.size > 1 and np.any(np.diff(self.times_s) <= 0):
            raise ValueError("forecast times must be strictly ascending")
        self._data = np.ascontiguousarray(data)
        #: the forecast's own valid times (`coverage.bounded_in_time` adds edge slices)
        self.forecast_times_s = self.times_s
        # the kernel reads half precision as its bit patterns (numba has no CPU float16)
        self.kernel_data = (self._data.view(np.uint16) if self._data.dtype == np.float16
                            else self._data)

    @property
    def nbytes(self) -> int:
        """Memory held by the sampler's field array."""
        return int(self._data.nbytes)

    @property
    def dtype(self) -> np.dtype:
        """Storage dtype of the fields (float32 or float16)."""
        return self._data.dtype

    def sample(self, lon_deg: np.ndarray, lat_deg: np.ndarray,
               time_s: np.ndarray) -> dict[str, np.ndarray]:
        """Interpolate every variable at the points; arrays broadcast to one shape.

        Returns float64 arrays of the broadcast shape keyed by canonical variable name.
        """
        lon_b, lat_b, t_b = np.broadcast_arrays(
            np.asarray(lon_deg, dtype=np.float64), np.asarray(lat_deg, dtype=np.float64),
            np.asarray(time_s, dtype=np.float64))
        shape = lon_b.shape
        lon_f = np.ascontiguousarray(lon_b).reshape(-1)
        lat_f = np.ascontiguousarray(lat_b).reshape(-1)
        t_f = np.ascontiguousarray(t_b).reshape(-1)
        out = np.empty((self._data.shape[3], lon_f.size), dtype=np.float64)
        g = self.grid
        trilinear(self.kernel_data, self.times_s, g.lat0_deg, g.dlat_deg, g.lon0_deg,
                  g.dlon_deg, g.is_global_in_lon, lon_f, lat_f, t_f, out)
        result: dict[str, np.ndarray] = {}
        c = 0
        for n in self.variables:
            if n in DIRECTION_VARIABLES:
                deg = np.rad2deg(np.arctan2(out[c], out[c + 1])) % 360.0
                result[n] = deg.reshape(shape)
                c += 2
            else:
                result[n] = out[c].reshape(shape)
                c += 1
        return result


def _storage_dtype(dtype: np.dtype | type) -> np.dtype:
    dt = np.dtype(dtype)
    if dt not in STORAGE_DTYPES:
        raise ValueError(f"sampler storage dtype must be float32 or float16, got {dt}")
    return dt
