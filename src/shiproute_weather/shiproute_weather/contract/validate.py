"""Physical-range and contract checks of a canonical dataset (NaN is allowed: missing)."""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np
import xarray as xr

from ..errors import GridError, MissingVariableError, ValueRangeError
from . import canonical as cv
from .limits import CURRENT_SPEED_MAX_M_S, WIND_SPEED_MAX_M_S
from .members import MEMBER_DIM, MEMBER_DIMS_ORDER, check_members

#: Physical limits (the same as `outliers`, which masks what lies beyond them when a file is
#: read): Hs 0-30 m, |wind| < 100 m/s, periods 0-40 s, currents below 5 m/s, directions
#: 0-360 deg. A dataset built in memory that breaks them is refused here.
__all__ = ["validate"]


def _check_range(ds: xr.Dataset, name: str, where: str) -> None:
    spec = cv.VARIABLES[name]
    a = ds[name].values
    lo = float(np.fmin.reduce(a, axis=None))  # fmin/fmax skip NaN without copying
    hi = float(np.fmax.reduce(a, axis=None))
    if np.isnan(lo):
        return  # all missing
    if np.isinf(lo) or np.isinf(hi):
        raise ValueRangeError(where, name, "holds infinite values", "finite values or NaN")
    if lo < spec.valid_min or hi > spec.valid_max:
        raise ValueRangeError(where, name, f"spans {lo:.6g}..{hi:.6g} {spec.units}",
                              f"{spec.long_name} within {spec.valid_min:g}..{spec.valid_max:g} "
                              f"{spec.units}")


def _check_speed(ds: xr.Dataset, u: str, v: str, limit: float, where: str) -> None:
    if u in ds and v in ds:
        a, b = ds[u].values, ds[v].values
        top2 = float(np.fmax.reduce(a * a + b * b, axis=None))
        top = float(np.sqrt(top2)) if np.isfinite(top2) else 0.0
        if top >= limit:
            raise ValueRangeError(where, f"{u}/{v}", f"reach a speed of {top:.6g} m s-1",
                                  f"speeds below {limit:g} m s-1")


def validate(ds: xr.Dataset, where: str = "dataset",
             required: Iterable[str] = ()) -> xr.Dataset:
    """Check attrs, grid, members, required variables and physical ranges (every member like a
    deterministic field); return `ds` unchanged."""
    for attr in cv.REQUIRED_ATTRS:
        if not ds.attrs.get(attr):
            raise GridError(where, f"attribute {attr!r} missing")
    grid = cv.grid_of(ds, where)
    if not (grid.lat0_deg >= -90.0 and grid.latitudes_deg[-1] <= 90.0):
        raise GridError(where, "latitudes outside -90..90")
    t = ds["time"].values
    if t.size > 1 and np.any(np.diff(t.astype(np.int64)) <= 0):
        raise GridError(where, "times are not strictly ascending")
    cv.require_variables(ds, list(required), where)
    present = cv.present_variables(ds)
    if not present:
        raise MissingVariableError(where, "any canonical variable",
                                   ", ".join(cv.CANONICAL_ORDER))
    check_members(ds, where)
    dims = MEMBER_DIMS_ORDER if MEMBER_DIM in ds.dims else ("time", "latitude", "longitude")
    for name in present:
        if ds[name].dims != dims:
            raise GridError(where, f"variable {name!r} has dims {ds[name].dims}; expected "
                                   f"({', '.join(dims)})")
        _check_range(ds, name, where)
    _check_speed(ds, cv.WIND_U, cv.WIND_V, WIND_SPEED_MAX_M_S, where)
    _check_speed(ds, cv.CURRENT_U, cv.CURRENT_V, CURRENT_SPEED_MAX_M_S, where)
    return ds
