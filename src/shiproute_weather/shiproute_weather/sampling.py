"""Vectorised sampling of a canonical forecast at arbitrary (longitude, latitude, time) points."""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np
import xarray as xr

from ._interp_kernel import MIN_VALID_WEIGHT, trilinear
from .canonical import DIRECTION_VARIABLES, grid_of, present_variables, times_posix_s
from .errors import MissingVariableError

__all__ = ["MIN_VALID_WEIGHT", "ForecastSampler"]


class ForecastSampler:
    """Trilinear interpolation in (time, latitude, longitude) of a canonical dataset.

    Longitudes are wrapped into the grid's range (and across the seam of a global grid);
    times outside the grid are clamped to its first/last valid time; points outside the
    latitude range or outside a regional longitude range give NaN. NaN nodes (e.g. land in a
    wave model) are skipped and the remaining weights renormalised when they carry at least
    `MIN_VALID_WEIGHT` of the total, else the result is NaN. Directions are interpolated as
    unit vectors (so 350 and 10 deg average to 0, not 180).

    The fields are copied once into a (time, lat, lon, channel) float32 array so each sample
    reads its 8 corners from contiguous memory; `sample` runs a parallel numba kernel.
    """

    def __init__(self, ds: xr.Dataset, variables: Iterable[str] | None = None) -> None:
        names = present_variables(ds) if variables is None else list(variables)
        for n in names:
            if n not in ds.data_vars:
                raise MissingVariableError(ds.attrs.get("cycle_id", "dataset"), n,
                                           "a variable present in the forecast dataset")
        self.variables: tuple[str, ...] = tuple(names)
        self.grid = grid_of(ds)
        self.times_s = np.ascontiguousarray(times_posix_s(ds))
        if self.times_s.size > 1 and np.any(np.diff(self.times_s) <= 0):
            raise ValueError("forecast times must be strictly ascending")
        nt, nlat, nlon = self.times_s.size, self.grid.n_lat, self.grid.n_lon
        n_ch = sum(2 if n in DIRECTION_VARIABLES else 1 for n in names)
        data = np.empty((nt, nlat, nlon, n_ch), dtype=np.float32)
        c = 0
        for n in names:
            values = ds[n].transpose("time", "latitude", "longitude").values
            if n in DIRECTION_VARIABLES:
                rad = np.deg2rad(values.astype(np.float32))
                data[..., c] = np.sin(rad)
                data[..., c + 1] = np.cos(rad)
                c += 2
            else:
                data[..., c] = values
                c += 1
        self._data = data

    @property
    def nbytes(self) -> int:
        """Memory held by the sampler's field array."""
        return int(self._data.nbytes)

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
        trilinear(self._data, self.times_s, g.lat0_deg, g.dlat_deg, g.lon0_deg, g.dlon_deg,
                  g.is_global_in_lon, lon_f, lat_f, t_f, out)
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
