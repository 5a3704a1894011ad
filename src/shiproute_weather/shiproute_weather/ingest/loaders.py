"""Open forecast files (GRIB1/2, NetCDF3/4) and turn them into one canonical dataset."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np
import xarray as xr

from ..contract import canonical as cv
from ..contract.members import (
    MEMBER_DIM,
    member_count,
    member_labels,
    select_member,
    stack_members,
)
from ..contract.validate import validate
from ..errors import ForecastFileError, MissingVariableError, WeatherError
from .combine import combine
from .grib import open_grib
from .normalise import to_canonical
from .wind_waves import estimate_waves, has_waves


def detect_format(path: Path) -> str:
    """'grib' or 'netcdf' from the file's first bytes."""
    try:
        with path.open("rb") as f:
            head = f.read(8)
    except OSError as exc:
        raise ForecastFileError(str(path), f"cannot be opened ({exc.strerror})") from exc
    if head.startswith(b"GRIB"):
        return "grib"
    if head.startswith((b"CDF\x01", b"CDF\x02", b"CDF\x05", b"\x89HDF")):
        return "netcdf"
    if not head:
        raise ForecastFileError(str(path), "file is empty")
    raise ForecastFileError(str(path), f"unknown format (first bytes {head[:4]!r}); expected "
                                       "GRIB or NetCDF")


NETCDF_CHUNK_CACHE_BYTES = 1 << 20
_CF_DECODE_ATTRS = ("scale_factor", "add_offset", "_FillValue", "missing_value")


def _decode_array(var: xr.Variable) -> np.ndarray:
    """CF mask/scale decoding without the extra full-size copies xarray's lazy decoding makes.

    The raw array is read once and scaled/masked in place (a NaN fill value needs no mask).
    """
    enc = var.attrs
    a = var.values
    scale = enc.get("scale_factor")
    offset = enc.get("add_offset")
    mask = None
    for key in ("_FillValue", "missing_value"):
        for v in np.atleast_1d(enc.get(key, [])):
            if isinstance(v, float | np.floating) and np.isnan(v):
                continue
            m = a == v
            mask = m if mask is None else mask | m
    if scale is not None or offset is not None or mask is not None:
        if a.dtype.kind != "f" or scale is not None or offset is not None:
            a = a.astype(np.float32 if a.dtype.itemsize <= 2 else np.float64)
        if scale is not None:
            a *= scale
        if offset is not None:
            a += offset
        if mask is not None:
            a[mask] = np.nan
    return a


def decode_variables(ds: xr.Dataset) -> xr.Dataset:
    """Copy of `ds` with every data variable read, and CF-decoded when it has >= 2 dims.

    The new arrays are swapped in with one `Dataset.copy(data=...)`: assigning variables one
    by one would re-align the whole dataset per variable, which costs more than the reading.
    The decoding attributes are dropped from the decoded variables; `ds` is not changed.
    """
    decoded = [name for name in ds.data_vars if ds.variables[name].ndim >= 2]
    data = {name: _decode_array(ds.variables[name]) if name in decoded
            else ds.variables[name].values for name in ds.data_vars}
    out = ds.copy(data=data)
    for name in decoded:
        for key in _CF_DECODE_ATTRS:
            out.variables[name].attrs.pop(key, None)
    return out


def open_netcdf_raw(path: Path) -> xr.Dataset:
    """Open a NetCDF file fully into memory (netcdf4 engine, h5netcdf as fallback).

    Data variables are read undecoded and decoded in place (one array per variable in
    memory); coordinates and times are decoded by xarray as usual.
    """
    import netCDF4

    # netCDF-C keeps up to 64 MB of decompressed chunks per variable by default, which
    # doubles peak memory when every variable is read once; 1 MB is enough for one pass.
    netCDF4.set_chunk_cache(NETCDF_CHUNK_CACHE_BYTES, 61, 0.75)
    last: Exception | None = None
    for engine in ("netcdf4", "h5netcdf"):
        try:
            with xr.open_dataset(path, engine=engine, decode_timedelta=True,
                                 mask_and_scale=False) as ds:
                out = decode_variables(ds)
                for name in out.coords:
                    out[name].load()
                return out
        except Exception as exc:
            last = exc
    raise ForecastFileError(str(path), f"cannot be read as NetCDF ({last})")


def open_file(path: str | Path) -> xr.Dataset:
    """One forecast file as a canonical dataset (not yet validated)."""
    p = Path(path)
    if not p.exists():
        raise ForecastFileError(str(p), "file does not exist")
    raw = open_grib(p) if detect_format(p) == "grib" else open_netcdf_raw(p)
    try:
        return to_canonical(raw, str(p))
    except WeatherError:
        raise
    except Exception as exc:
        raise ForecastFileError(str(p), f"cannot be interpreted as a forecast ({exc})") from exc


def open_forecast(paths: Sequence[str | Path], required: Sequence[str] = (),
                  cycle_id: str | None = None, waves_from_wind: bool = True) -> xr.Dataset:
    """Load, combine and validate forecast files into one canonical dataset (one cycle).

    Several files are combined onto the grid/times of the first one holding wind (see
    `combine.combine`); every field keeps its source file. A cycle with wind but no waves gets
    a wind sea estimated from the wind (`wind_waves`, stated in the dataset's
    `waves_estimated` attribute), or is refused with `waves_from_wind=False`. `required`
    canonical variables must be present after combining.
    """
    if not paths:
        raise ForecastFileError("(no files)", "no forecast files given")
    datasets = [validate(open_file(p), str(p)) for p in paths]
    ds = combine(datasets)
    if cycle_id:
        ds.attrs["cycle_id"] = cycle_id
    where = ", ".join(str(p) for p in paths)
    if cv.WIND_U in ds and not has_waves(ds):
        if not waves_from_wind:
            raise MissingVariableError(where, cv.WAVE_HS, "wave fields (the forecast has wind "
                                       "only; allow estimating waves from wind to use it)")
        ds = _estimate_member_waves(ds) if MEMBER_DIM in ds.dims else estimate_waves(ds)
    return validate(ds, where, required)


def _estimate_member_waves(ds: xr.Dataset) -> xr.Dataset:
    """Waves grown from each member's own wind (the members keep their labels and kind)."""
    grown = [estimate_waves(select_member(ds, k)) for k in range(member_count(ds))]
    out = stack_members(grown, member_labels(ds), str(ds.attrs.get("member_kind", "ensemble")))
    for key in ("ensemble", "member_sources", "source_files", "source"):
        if key in ds.attrs:
            out.attrs[key] = ds.attrs[key]
    return out
