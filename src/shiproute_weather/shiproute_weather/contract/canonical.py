"""Canonical forecast dataset contract: variable names, units, conventions, grid checks."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..errors import GridError, MissingVariableError

if TYPE_CHECKING:  # annotations only: the planner need not keep xarray + pandas resident
    import xarray as xr

WIND_U = "eastward_wind"
WIND_V = "northward_wind"
WAVE_HS = "sea_surface_wave_significant_height"
WAVE_DIR = "sea_surface_wave_from_direction"
WAVE_TM = "sea_surface_wave_mean_period"
WIND_WAVE_HS = "sea_surface_wind_wave_significant_height"
WIND_WAVE_DIR = "sea_surface_wind_wave_from_direction"
WIND_WAVE_TM = "sea_surface_wind_wave_mean_period"
SWELL_HS = "sea_surface_swell_wave_significant_height"
SWELL_DIR = "sea_surface_swell_wave_from_direction"
SWELL_TM = "sea_surface_swell_wave_mean_period"
CURRENT_U = "eastward_sea_water_velocity"
CURRENT_V = "northward_sea_water_velocity"


@dataclass(frozen=True)
class VariableSpec:
    """Units, direction convention and physical range of one canonical variable."""

    units: str
    direction_convention: str  # "" scalar, "coming_from", "going_to"
    valid_min: float
    valid_max: float
    long_name: str


_HS = (0.0, 30.0)  # impossible values beyond: see outliers.py
_T = (0.0, 40.0)
_DIR = (0.0, 360.0)

VARIABLES: dict[str, VariableSpec] = {
    WIND_U: VariableSpec("m s-1", "going_to", -100.0, 100.0, "10 m eastward wind"),
    WIND_V: VariableSpec("m s-1", "going_to", -100.0, 100.0, "10 m northward wind"),
    WAVE_HS: VariableSpec("m", "", *_HS, "significant height of total sea"),
    WAVE_DIR: VariableSpec("degree", "coming_from", *_DIR, "mean direction of total sea"),
    WAVE_TM: VariableSpec("s", "", *_T, "mean period Tm01 of total sea"),
    WIND_WAVE_HS: VariableSpec("m", "", *_HS, "significant height of wind sea"),
    WIND_WAVE_DIR: VariableSpec("degree", "coming_from", *_DIR, "mean direction of wind sea"),
    WIND_WAVE_TM: VariableSpec("s", "", *_T, "mean period Tm01 of wind sea"),
    SWELL_HS: VariableSpec("m", "", *_HS, "significant height of primary swell"),
    SWELL_DIR: VariableSpec("degree", "coming_from", *_DIR, "mean direction of primary swell"),
    SWELL_TM: VariableSpec("s", "", *_T, "mean period Tm01 of primary swell"),
    CURRENT_U: VariableSpec("m s-1", "going_to", -10.0, 10.0, "surface eastward current"),
    CURRENT_V: VariableSpec("m s-1", "going_to", -10.0, 10.0, "surface northward current"),
}

DIRECTION_VARIABLES = frozenset(n for n, s in VARIABLES.items() if s.units == "degree")
CANONICAL_ORDER: tuple[str, ...] = tuple(VARIABLES)
REQUIRED_ATTRS = ("forecast_reference_time", "source", "cycle_id")


@dataclass(frozen=True)
class Grid:
    """Regular latitude/longitude grid: node (i, j) at (lat0 + i dlat, lon0 + j dlon)."""

    lat0_deg: float
    dlat_deg: float
    n_lat: int
    lon0_deg: float
    dlon_deg: float
    n_lon: int

    @property
    def latitudes_deg(self) -> np.ndarray:
        return self.lat0_deg + self.dlat_deg * np.arange(self.n_lat)

    @property
    def longitudes_deg(self) -> np.ndarray:
        return self.lon0_deg + self.dlon_deg * np.arange(self.n_lon)

    @property
    def is_global_in_lon(self) -> bool:
        """True when the columns wrap round the whole globe (last column + dlon == first)."""
        return abs(self.n_lon * self.dlon_deg - 360.0) < 1e-6 * max(1.0, self.dlon_deg)


def regular_spacing(values: np.ndarray, name: str, where: str) -> float:
    """Return the constant spacing of ascending `values`, or raise GridError."""
    if values.size < 2:
        raise GridError(where, f"coordinate {name!r} needs at least 2 values, got {values.size}")
    d = np.diff(values.astype(np.float64))
    step = float(d.mean())
    if step <= 0 or np.max(np.abs(d - step)) > 1e-4 * abs(step) + 1e-9:
        raise GridError(where, f"coordinate {name!r} is not regular and ascending")
    return step


def grid_of(ds: xr.Dataset, where: str = "dataset") -> Grid:
    """Grid of a canonical dataset (checks ascending, regular latitude and longitude)."""
    for coord in ("time", "latitude", "longitude"):
        if coord not in ds.coords:
            raise GridError(where, f"coordinate {coord!r} missing; expected dims "
                                   "(time, latitude, longitude)")
    lat = ds["latitude"].values.astype(np.float64)
    lon = ds["longitude"].values.astype(np.float64)
    dlat = regular_spacing(lat, "latitude", where)
    dlon = regular_spacing(lon, "longitude", where)
    return Grid(float(lat[0]), dlat, lat.size, float(lon[0]), dlon, lon.size)


def times_posix_s(ds: xr.Dataset) -> np.ndarray:
    """Valid times of a canonical dataset as POSIX seconds (float64, UTC)."""
    t = ds["time"].values.astype("datetime64[ns]").astype(np.int64)
    return t.astype(np.float64) / 1e9


def present_variables(ds: xr.Dataset) -> list[str]:
    """Canonical variables present in `ds`, in canonical order."""
    return [n for n in CANONICAL_ORDER if n in ds.data_vars]


def require_variables(ds: xr.Dataset, names: list[str], where: str = "dataset") -> None:
    """Raise MissingVariableError for the first of `names` absent from `ds`."""
    for n in names:
        if n not in ds.data_vars:
            spec = VARIABLES.get(n)
            expected = f"{spec.long_name} [{spec.units}]" if spec else "a canonical variable"
            raise MissingVariableError(where, n, expected)


def annotate(ds: xr.Dataset) -> xr.Dataset:
    """Set CF attributes (standard_name, units, conventions) on canonical variables and coords."""
    for n in present_variables(ds):
        spec = VARIABLES[n]
        ds[n].attrs.update(
            standard_name=n, units=spec.units, long_name=spec.long_name,
            direction_convention=spec.direction_convention,
        )
    ds["latitude"].attrs.update(standard_name="latitude", units="degrees_north")
    ds["longitude"].attrs.update(standard_name="longitude", units="degrees_east")
    ds["time"].attrs.update(standard_name="time")
    ds.attrs.setdefault("Conventions", "CF-1.8")
    return ds
