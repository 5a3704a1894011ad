"""Vectorised sampling of a canonical forecast at arbitrary (longitude, latitude, time) points."""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from typing import TYPE_CHECKING

import numpy as np

from ._half_kernel import interleave_half_bits
from ._interp_kernel import MIN_VALID_WEIGHT, trilinear
from .canonical import DIRECTION_VARIABLES, Grid, grid_of, present_variables, times_posix_s
from .errors import MissingVariableError

if TYPE_CHECKING:  # xarray is only needed by whoever passes a Dataset
    import xarray as xr

__all__ = ["MIN_VALID_WEIGHT", "STORAGE_DTYPES", "ForecastSampler", "channel_count",
           "pack_fields"]

#: dtypes the sampler can keep its fields in: float32 (default) or IEEE half precision, whose
#: relative rounding (2^-11) is below the packing precision of the forecast sources themselves
STORAGE_DTYPES = (np.dtype(np.float32), np.dtype(np.float16))


def channel_count(variables: Iterable[str]) -> int:
    """Channels of the packed array: one per scalar, two (sine, cosine) per direction."""
    return sum(2 if n in DIRECTION_VARIABLES else 1 for n in variables)


def pack_fields(out: np.ndarray, variables: Sequence[str],
                values_of: Callable[[str], np.ndarray]) -> None:
    """Fill `out` (..., channel) with the fields `values_of(name)` (shape out.shape[:-1]):
    scalars as they are, directions [deg] as the sine and cosine of the angle. A float16
    `out` is written in one sequential pass by `interleave_half_bits` (numpy's float16
    conversion through strided channel columns is ~4x slower, and this runs for every slice
    of every cycle the planner receives)."""
    columns: list[np.ndarray] = []
    for n in variables:
        values = values_of(n)
        if n in DIRECTION_VARIABLES:
            rad = np.deg2rad(np.asarray(values, dtype=np.float32))
            columns += [np.sin(rad), np.cos(rad)]
        else:
            columns.append(values)
    if out.dtype == np.float16:
        bits = tuple(_readonly_bits(v) for v in columns)
        interleave_half_bits(bits, out.reshape(-1, out.shape[-1]).view(np.uint16))
    else:
        for c, v in enumerate(columns):
            out[..., c] = v


def _readonly_bits(values: np.ndarray) -> np.ndarray:
    """float32 values as a flat read-only uint32 view: one array type for numba whether the
    source is a message buffer (read-only bytes) or a computed array."""
    bits = np.ascontiguousarray(values, dtype=np.float32).reshape(-1).view(np.uint32)
    bits.flags.writeable = False
    return bits


class ForecastSampler:
    """Trilinear interpolation in (time, latitude, longitude) of a canonical dataset.

    Longitudes are wrapped into the grid's range (and across the seam of a global grid);
    times outside the grid are clamped to its first/last valid time; points outside the
    latitude range or outside a regional longitude range give NaN. NaN nodes (e.g. land in a
    wave model) are skipped and the remaining weights renormalised when they carry at least
    `MIN_VALID_WEIGHT` of the total, else the result is NaN. Directions are interpolated as
    unit vectors (so 350 and 10 deg average to 0, not 180).

    The fields are copied once into a (time, lat, lon, channel) array (float32, or float16
    with `dtype=np.float16` at half the memory) so each sample reads its 8 corners from
    contiguous memory; `sample` runs a parallel numba kernel. `from_packed` wraps an array
    packed elsewhere (e.g. slice by slice as a cycle arrives) without another copy.
    """

    def __init__(self, ds: xr.Dataset, variables: Iterable[str] | None = None,
                 dtype: np.dtype | type = np.float32) -> None:
        names = present_variables(ds) if variables is None else list(variables)
        for n in names:
            if n not in ds.data_vars:
                raise MissingVariableError(ds.attrs.get("cycle_id", "dataset"), n,
                                           "a variable present in the forecast dataset")
        grid = grid_of(ds)
        times_s = times_posix_s(ds)
        data = np.empty((times_s.size, grid.n_lat, grid.n_lon, channel_count(names)),
                        dtype=_storage_dtype(dtype))
        pack_fields(data, names, lambda n: ds[n].transpose("time", "latitude",
                                                           "longitude").values)
        self._init(data, times_s, grid, names)

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
        self.grid = grid
        self.times_s = np.ascontiguousarray(times_s, dtype=np.float64)
        if self.times_s.size > 1 and np.any(np.diff(self.times_s) <= 0):
            raise ValueError("forecast times must be strictly ascending")
        self._data = np.ascontiguousarray(data)
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
