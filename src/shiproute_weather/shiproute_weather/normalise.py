"""Turn a raw provider dataset (any supported naming convention) into the canonical dataset."""

from __future__ import annotations

import re

import numpy as np
import xarray as xr

from . import canonical as cv
from .coords import (
    ascending_latitude,
    make_regular_lonlat,
    normalise_longitude,
    rename_coords,
    utc_naive_times,
)
from .errors import MissingVariableError
from .namemap import (
    CURRENT_DIR_NAMES,
    CURRENT_SPEED_NAMES,
    WIND_DIR_NAMES,
    WIND_SPEED_NAMES,
    Mapping,
    lookup,
)
from .slices import snap_grid
from .spectral import to_tm01_factor
from .timefmt import canonical_iso
from .units import si_factor

_DIMS = ("time", "latitude", "longitude")
_EXPECTED = ("wind (u10/v10, UGRD/VGRD, eastward_wind...), waves (swh, HTSGW, VHM0, "
             "sea_surface_wave_significant_height...) or currents (uo/vo, utotal/vtotal...)")


def _units(da: xr.DataArray) -> str | None:
    return da.attrs.get("units") or da.attrs.get("GRIB_units")


def _surface(da: xr.DataArray) -> xr.DataArray:
    """Drop extra dims (ensemble member, depth, height level): keep the surface / first one."""
    for d in [d for d in da.dims if d not in _DIMS]:
        if d in da.coords and d.lower().startswith("depth"):
            da = da.isel({d: int(np.argmin(np.abs(da[d].values)))}, drop=True)
        else:
            da = da.isel({d: 0}, drop=True)
    return da.drop_vars([c for c in da.coords if c not in _DIMS], errors="ignore")


def _choose(ds: xr.Dataset) -> dict[str, tuple[str, Mapping]]:
    best: dict[str, tuple[int, str, Mapping]] = {}
    for name in ds.data_vars:
        m = lookup(str(name), ds[name].attrs.get("standard_name"))
        if m is None:
            continue
        cur = best.get(m.canonical)
        if cur is None or m.priority < cur[0]:
            best[m.canonical] = (m.priority, str(name), m)
    return {k: (n, m) for k, (_, n, m) in best.items()}


def _find_named(ds: xr.Dataset, names: tuple[str, ...], standard: str) -> str | None:
    for n in ds.data_vars:
        if str(n).lower() in names or ds[n].attrs.get("standard_name") == standard:
            return str(n)
    return None


def _convert(da: xr.DataArray, m: Mapping, where: str) -> np.ndarray:
    spec = cv.VARIABLES[m.canonical]
    vals = da.values if da.dims == _DIMS else _surface(da).transpose(*_DIMS).values
    factor = si_factor(_units(da), spec.units, where, str(da.name))
    if spec.units == "s" and m.period_kind != "tm01":
        factor *= to_tm01_factor(m.period_kind)
    if factor != 1.0 or vals.dtype != np.float32:
        vals = vals.astype(np.float64) * factor
    if spec.units == "degree":
        lo, hi = np.fmin.reduce(vals, axis=None), np.fmax.reduce(vals, axis=None)  # skip NaN
        if m.going_to or lo < 0.0 or hi >= 360.0:
            vals = (vals.astype(np.float64) + (180.0 if m.going_to else 0.0)) % 360.0
    return vals


def _speed_dir_pairs(ds: xr.Dataset, out: dict[str, np.ndarray], where: str) -> None:
    """Wind speed + from-direction, current speed + to-direction -> u/v components."""
    pairs = ((cv.WIND_U, cv.WIND_V, WIND_SPEED_NAMES, "wind_speed", WIND_DIR_NAMES,
              "wind_from_direction", -1.0),
             (cv.CURRENT_U, cv.CURRENT_V, CURRENT_SPEED_NAMES, "sea_water_speed",
              CURRENT_DIR_NAMES, "direction_of_sea_water_velocity", 1.0))
    for u_name, v_name, sp_names, sp_std, dir_names, dir_std, sign in pairs:
        if u_name in out:
            continue
        s, d = _find_named(ds, sp_names, sp_std), _find_named(ds, dir_names, dir_std)
        if s is None or d is None:
            continue
        speed = _surface(ds[s]).transpose(*_DIMS).values.astype(np.float64)
        speed = speed * si_factor(_units(ds[s]), "m s-1", where, s)
        rad = np.deg2rad(_surface(ds[d]).transpose(*_DIMS).values.astype(np.float64)
                         * si_factor(_units(ds[d]), "degree", where, d))
        out[u_name] = sign * speed * np.sin(rad)
        out[v_name] = sign * speed * np.cos(rad)


def _slug(text: str) -> str:
    return re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-")[:40] or "forecast"


def to_canonical(raw: xr.Dataset, where: str) -> xr.Dataset:
    """Canonical dataset from a raw one: names, SI units, directions, grid, UTC times."""
    ds = rename_coords(raw, where)
    ds = make_regular_lonlat(ds, where)
    chosen = _choose(ds)
    out = {c: _convert(ds[n], m, where) for c, (n, m) in chosen.items()}
    _speed_dir_pairs(ds, out, where)
    if not out:
        raise MissingVariableError(where, "any forecast variable", _EXPECTED)
    data = {c: (_DIMS, out[c].astype(np.float32, copy=False)) for c in cv.CANONICAL_ORDER
            if c in out}
    res = xr.Dataset(data, coords={"time": ds["time"].values, "latitude": ds["latitude"].values,
                                   "longitude": ds["longitude"].values})
    res = utc_naive_times(ascending_latitude(normalise_longitude(res, where)), where)
    res = snap_grid(res)
    attrs = raw.attrs
    ref = attrs.get("forecast_reference_time")
    if not ref and "forecast_reference_time" in raw.variables:
        ref = np.datetime_as_string(np.atleast_1d(raw["forecast_reference_time"].values)[0],
                                    unit="s") + "Z"
    if not ref:
        ref = np.datetime_as_string(res["time"].values[0], unit="s") + "Z"
    source = str(attrs.get("source") or attrs.get("institution") or attrs.get("title")
                 or "unknown")
    ref = canonical_iso(str(ref))
    cycle = str(attrs.get("cycle_id") or f"{_slug(source)}-{re.sub(r'[^0-9]', '', ref)[:10]}")
    res.attrs = {"forecast_reference_time": ref, "source": source, "cycle_id": cycle}
    return cv.annotate(res)
