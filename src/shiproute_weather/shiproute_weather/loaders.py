"""Open forecast files (NetCDF, GRIB2) and turn them into one canonical dataset."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import xarray as xr

from .canonical import annotate
from .errors import ForecastFileError


def open_netcdf_raw(path: Path) -> xr.Dataset:
    """Open a NetCDF file fully into memory (netcdf4 engine, h5netcdf as fallback)."""
    last: Exception | None = None
    for engine in ("netcdf4", "h5netcdf"):
        try:
            with xr.open_dataset(path, engine=engine, decode_timedelta=True) as ds:
                return ds.load()
        except Exception as exc:
            last = exc
    raise ForecastFileError(str(path), f"cannot be read as NetCDF ({last})")


def open_forecast(paths: Sequence[str | Path]) -> xr.Dataset:
    """Load one or more forecast files into a canonical dataset."""
    path = Path(paths[0])
    if not path.exists():
        raise ForecastFileError(str(path), "file does not exist")
    ds = open_netcdf_raw(path)
    return annotate(ds.sortby("latitude"))
