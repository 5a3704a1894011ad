"""Coordinate normalisation: names, reduced grids, longitude range/continuity, latitude order."""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..errors import GridError

_LAT = ("latitude", "lat", "nav_lat", "y_lat", "lat_rho")
_LON = ("longitude", "lon", "nav_lon", "x_lon", "lon_rho")
_TIME = ("time", "valid_time", "t", "time1", "forecast_time", "date")


def _find(ds: xr.Dataset, names: tuple[str, ...], standard: str) -> str | None:
    for n in names:
        if n in ds.coords or n in ds.dims:
            return n
    for name, c in ds.coords.items():
        if c.attrs.get("standard_name") == standard or c.attrs.get("axis") == standard[:1].upper():
            return str(name)
    return None


def rename_coords(ds: xr.Dataset, where: str) -> xr.Dataset:
    """Rename latitude/longitude/time coordinates to canonical names; add a time dim if absent."""
    lat = _find(ds, _LAT, "latitude")
    lon = _find(ds, _LON, "longitude")
    if lat is None or lon is None:
        raise GridError(where, "no latitude/longitude coordinates found (looked for "
                               f"{', '.join(_LAT + _LON)} and CF standard_name)")
    t = _find(ds, _TIME, "time")
    mapping = {k: v for k, v in ((lat, "latitude"), (lon, "longitude"), (t, "time"))
               if k is not None and k != v}
    ds = ds.rename(mapping)
    if "time" not in ds.coords:
        raise GridError(where, "no time coordinate found; expected a valid time axis")
    if "time" not in ds.dims:
        ds = ds.expand_dims("time")
    return ds


def regrid_reduced(ds: xr.Dataset, dim: str) -> xr.Dataset:
    """Turn a reduced (row-wise varying longitude count) grid on 1-D `dim` into a regular grid.

    Each latitude row is interpolated linearly and periodically in longitude onto the
    longitudes of the densest row.
    """
    lat = ds["latitude"].values
    lon = ds["longitude"].values % 360.0
    rows = np.unique(lat)[::-1]
    n_max = max(int(np.sum(lat == r)) for r in rows)
    lon_out = np.arange(n_max) * (360.0 / n_max)
    out = {}
    for name, da in ds.data_vars.items():
        if dim not in da.dims:
            continue
        other = [d for d in da.dims if d != dim]
        vals = da.transpose(*other, dim).values
        grid = np.full((*vals.shape[:-1], rows.size, n_max), np.nan, dtype=np.float64)
        for i, r in enumerate(rows):
            sel = np.nonzero(lat == r)[0]
            lo = lon[sel]
            order = np.argsort(lo)
            lo_s = np.concatenate([lo[order], [lo[order][0] + 360.0]])
            v = vals[..., sel[order]]
            v = np.concatenate([v, v[..., :1]], axis=-1)
            idx = np.clip(np.searchsorted(lo_s, lon_out, side="right") - 1, 0, lo_s.size - 2)
            w = (lon_out - lo_s[idx]) / (lo_s[idx + 1] - lo_s[idx])
            grid[..., i, :] = v[..., idx] * (1 - w) + v[..., idx + 1] * w
        out[name] = ((*other, "latitude", "longitude"), grid, da.attrs)
    coords = {k: v for k, v in ds.coords.items() if dim not in v.dims}
    coords.update(latitude=rows, longitude=lon_out)
    return xr.Dataset(out, coords=coords, attrs=ds.attrs)


def make_regular_lonlat(ds: xr.Dataset, where: str) -> xr.Dataset:
    """Regrid 1-D point grids (reduced lat/lon or Gaussian) to regular; 2-D coords rejected."""
    if ds["latitude"].ndim == 1 and ds["latitude"].dims == ds["longitude"].dims and \
            ds["latitude"].dims[0] not in ("latitude",):
        return regrid_reduced(ds, str(ds["latitude"].dims[0]))
    if ds["latitude"].ndim == 2 and ds["longitude"].dims == ds["latitude"].dims:
        from .projected import regrid_projected  # pyproj only for projected grids

        return regrid_projected(ds, where, _grid_relative_pairs(ds))
    if ds["latitude"].ndim != 1 or ds["longitude"].ndim != 1:
        raise GridError(where, "latitude/longitude coordinates of different shapes; expected "
                               "a regular or projected grid")
    return ds


def _grid_relative_pairs(ds: xr.Dataset) -> tuple[tuple[str, str], ...]:
    """(u, v) variable names whose components are along the grid's axes, not east/north:
    CF x_wind/y_wind, GRIB messages flagged uvRelativeToGrid."""
    from ..contract import canonical as cv
    from .namemap import lookup

    u = v = None
    for n, da in ds.data_vars.items():
        std = str(da.attrs.get("standard_name", ""))
        rel = std in ("x_wind", "y_wind") or int(da.attrs.get("GRIB_uvRelativeToGrid", 0)) == 1
        m = lookup(str(n), std)
        if rel and m is not None and m.canonical == cv.WIND_U:
            u = str(n)
        if rel and m is not None and m.canonical == cv.WIND_V:
            v = str(n)
    return ((u, v),) if u and v else ()


def normalise_longitude(ds: xr.Dataset, where: str) -> xr.Dataset:
    """Ascending, continuous longitudes: [0, 360) for global grids, a region crossing 180
    keeps increasing past 180 (e.g. 115..245), a region west of 180 uses -180..180."""
    lon = ds["longitude"].values.astype(np.float64) % 360.0
    order = np.argsort(lon, kind="stable")
    lon_sorted = lon[order]
    if lon_sorted.size > 1 and np.any(np.diff(lon_sorted) == 0):
        raise GridError(where, "duplicate longitudes after wrapping into 0..360")
    gaps = np.diff(np.concatenate([lon_sorted, [lon_sorted[0] + 360.0]]))
    k = int(np.argmax(gaps))
    typical = float(np.median(gaps)) if gaps.size else 0.0
    # a region begins after the largest gap; a global grid keeps 0..360
    start = (k + 1) % lon_sorted.size if gaps.size > 1 and gaps[k] > 1.5 * typical else 0
    order = np.roll(order, -start)
    new_lon = np.unwrap(lon[order], period=360.0)
    if new_lon[0] >= 180.0:
        new_lon = new_lon - 360.0
    if not np.array_equal(order, np.arange(order.size)):
        ds = ds.isel(longitude=order)
    if np.array_equal(new_lon, ds["longitude"].values):
        return ds
    return ds.assign_coords(longitude=new_lon)


def ascending_latitude(ds: xr.Dataset) -> xr.Dataset:
    """Latitude rows south -> north."""
    lat = ds["latitude"].values
    if lat.size > 1 and lat[0] > lat[-1]:
        ds = ds.isel(latitude=slice(None, None, -1))
    return ds


def utc_naive_times(ds: xr.Dataset, where: str) -> xr.Dataset:
    """Times as naive UTC datetime64[ns], ascending, unique."""
    t = ds["time"].values
    if not np.issubdtype(t.dtype, np.datetime64):
        raise GridError(where, f"time coordinate has dtype {t.dtype}; expected decodable CF "
                               "times (units 'hours since ...')")
    t = t.astype("datetime64[ns]")
    if t.dtype != ds["time"].dtype:
        ds = ds.assign_coords(time=t)
    if t.size > 1 and not np.all(np.diff(t.astype(np.int64)) > 0):
        _, idx = np.unique(t, return_index=True)  # sorts and drops repeated times
        ds = ds.isel(time=idx)
    return ds


def require_monotonic(ds: xr.Dataset, where: str) -> None:
    """Refuse coordinates that are not a grid axis: latitudes and valid times must be strictly
    monotonic; longitudes too, except for one wrap (e.g. 180..359 then 0..179)."""
    for name in ("latitude", "time"):
        v = ds[name].values
        if v.ndim != 1 or v.size < 2:
            continue
        d = np.diff(v.astype("datetime64[ns]").astype(np.int64) if name == "time"
                    else v.astype(np.float64))
        if not (np.all(d > 0) or (name == "latitude" and np.all(d < 0))):
            what = "valid times" if name == "time" else "latitudes"
            raise GridError(where, f"{what} are not monotonic (coordinate {name!r}); "
                                   "expected an ordered grid axis")
    lon = ds["longitude"].values
    if lon.ndim == 1 and lon.size > 2:
        d = np.diff(lon.astype(np.float64))
        up, down = int(np.sum(d > 0)), int(np.sum(d < 0))
        if np.any(d == 0) or min(up, down) > 1:
            raise GridError(where, "longitudes are not monotonic (coordinate 'longitude'); "
                                   "expected an ordered grid axis")


def regular_axes(ds: xr.Dataset, where: str) -> tuple[xr.Dataset, list[str]]:
    """Check that latitude and longitude are regular within 2 % of a step (ascending, as after
    normalising; Gaussian grids pass and are snapped to regular by `snap_grid`). A
    single irregular row or column at an edge (e.g. a pole row at 90 N after rows every
    1 deg from 89.46 N) is dropped and said; any other irregularity is refused."""
    notes = []
    for name in ("latitude", "longitude"):
        v = ds[name].values.astype(np.float64)
        if v.size < 3:
            continue
        d = np.diff(v)
        step = float(np.median(d))
        tol = 0.02 * abs(step) + 1e-9  # Gaussian latitudes deviate < 0.5 % from regular
        bad = np.flatnonzero(np.abs(d - step) > tol)
        if bad.size == 0:
            continue
        if bad.size == 1 and bad[0] in (0, d.size - 1):
            k = 0 if bad[0] == 0 else v.size - 1
            ds = ds.isel({name: np.delete(np.arange(v.size), k)})
            notes.append(f"{name} {v[k]:g} dropped: irregular spacing at the grid's edge "
                         f"({abs(d[bad[0]]):g} instead of {step:g} deg)")
            continue
        raise GridError(where, f"coordinate {name!r} is not regular (spacing {step:g} deg, "
                               f"{bad.size} steps differ)")
    return ds, notes
