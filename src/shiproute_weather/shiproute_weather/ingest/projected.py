"""Projected grids (Lambert conformal, polar stereographic, any CF grid mapping) regridded to a
regular latitude/longitude grid with pyproj.

The source gives 2-D latitude/longitude arrays on its (y, x) grid. They are projected with the
grid's projection (from its CF `grid_mapping` variable or its GRIB grid keys), and the grid
indices are fitted as an affine function of the projected coordinates: that holds for every
grid regular in its projection whatever its false origin, rotation or scale, and the fit's
residual (<= `MAX_FIT_RESIDUAL` of a cell) proves the projection right before any value is
used. Each node of the target grid is then projected, located in the source grid and
interpolated bilinearly (NaN outside). Grid-relative vector components (GRIB
`uvRelativeToGrid`, CF `x_wind`/`y_wind`) are turned to east/north with the local bearing of
the grid's x axis.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..errors import GridError

#: largest error of the affine index fit, in grid cells, for the projection to be accepted
MAX_FIT_RESIDUAL = 0.02
_NICE_STEPS_DEG = (0.01, 0.02, 0.025, 0.05, 0.1, 0.125, 0.2, 0.25, 0.5, 1.0, 2.0)
_EARTH_R_M = 6371229.0  # GRIB shape of the Earth 6 (the common one for these grids)


def _crs(ds: xr.Dataset, where: str):
    from pyproj import CRS

    for v in ds.data_vars.values():
        gm = v.attrs.get("grid_mapping")
        if gm and gm in ds.variables:
            try:
                return CRS.from_cf(dict(ds[gm].attrs))
            except Exception as exc:
                raise GridError(where, f"grid mapping {gm!r} is not understood ({exc})") from exc
    attrs = next(iter(ds.data_vars.values())).attrs
    kind = str(attrs.get("GRIB_gridType", ""))
    lat_mean = float(np.nanmean(ds["latitude"].values))
    if kind == "polar_stereographic":
        # any true-scale latitude and central meridian: they only scale and rotate the plane,
        # which the affine fit absorbs
        pole = 90 if lat_mean >= 0 else -90
        return CRS.from_proj4(f"+proj=stere +lat_0={pole} +lon_0=0 +R={_EARTH_R_M}")
    if kind == "lambert":
        try:
            lat1 = float(attrs["GRIB_Latin1InDegrees"])
            lat2 = float(attrs["GRIB_Latin2InDegrees"])
        except KeyError as exc:
            raise GridError(where, "Lambert conformal grid without its standard parallels "
                                   "(Latin1/Latin2)") from exc
        return CRS.from_proj4(f"+proj=lcc +lat_1={lat1} +lat_2={lat2} +lat_0={lat1} "
                              f"+lon_0=0 +R={_EARTH_R_M}")
    raise GridError(where, "curvilinear (2-D) latitude/longitude grid with no projection "
                           "(no CF grid_mapping, GRIB gridType "
                           f"{kind or 'unknown'}); expected a regular latitude/longitude, "
                           "Lambert conformal or polar stereographic grid")


def _label(ds: xr.Dataset) -> str:
    attrs = next(iter(ds.data_vars.values())).attrs
    kind = str(attrs.get("GRIB_gridType", "")) or "projected (CF grid mapping)"
    return {"lambert": "Lambert conformal", "polar_stereographic": "polar stereographic"
            }.get(kind, kind)


def _affine_fit(x: np.ndarray, y: np.ndarray, where: str) -> np.ndarray:
    """Least-squares (i, j) = M @ (x, y, 1) over every node; refused when it does not fit."""
    ny, nx = x.shape
    jj, ii = np.meshgrid(np.arange(nx), np.arange(ny))
    a = np.column_stack([x.ravel(), y.ravel(), np.ones(x.size)])
    ok = np.isfinite(a).all(axis=1)
    m, *_ = np.linalg.lstsq(a[ok], np.column_stack([ii.ravel(), jj.ravel()])[ok], rcond=None)
    resid = np.abs(a[ok] @ m - np.column_stack([ii.ravel(), jj.ravel()])[ok]).max()
    if not resid <= MAX_FIT_RESIDUAL:
        raise GridError(where, f"the grid is not regular in its stated projection (index fit "
                               f"off by {resid:.3g} cells)")
    return m


def _target_axes(lat2: np.ndarray, lon2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Regular axes covering the source grid at about its resolution (a 'nice' step)."""
    dlat = float(np.nanmedian(np.abs(np.diff(lat2, axis=0))))
    dlon_eq = float(np.nanmedian(np.abs((np.diff(lon2, axis=1) + 180.0) % 360.0 - 180.0)
                                 * np.cos(np.deg2rad(lat2[:, 1:]))))
    step = min(dlat, dlon_eq) if np.isfinite(dlon_eq) and dlon_eq > 0 else dlat
    step = max((s for s in _NICE_STEPS_DEG if s <= 1.1 * step), default=_NICE_STEPS_DEG[0])
    lat0, lat1 = np.ceil(np.nanmin(lat2) / step) * step, np.floor(np.nanmax(lat2) / step) * step
    lon = np.sort(np.unique(np.round(lon2[np.isfinite(lon2)] % 360.0, 6)))
    gaps = np.diff(np.concatenate([lon, [lon[0] + 360.0]]))
    k = int(np.argmax(gaps))
    if gaps[k] < 10.0 * step:  # round the pole: every longitude
        lon0, lon1 = 0.0, 360.0 - step
    else:  # the region starts after the largest gap and may run past 180
        first, last = lon[(k + 1) % lon.size], lon[k]
        last = last + 360.0 if last < first else last
        first = first - 360.0 if first >= 180.0 else first
        last = last - 360.0 if first < 0 and last - 360.0 > first else last
        lon0, lon1 = np.ceil(first / step) * step, np.floor(last / step) * step
    return (lat0 + step * np.arange(round((lat1 - lat0) / step) + 1),
            lon0 + step * np.arange(round((lon1 - lon0) / step) + 1))


def _bilinear(values: np.ndarray, fi: np.ndarray, fj: np.ndarray) -> np.ndarray:
    """values (..., ny, nx) at fractional indices (n,), NaN outside."""
    ny, nx = values.shape[-2:]
    inside = (fi >= 0) & (fi <= ny - 1) & (fj >= 0) & (fj <= nx - 1)
    i0 = np.clip(np.floor(fi).astype(int), 0, max(ny - 2, 0))
    j0 = np.clip(np.floor(fj).astype(int), 0, max(nx - 2, 0))
    wi, wj = np.clip(fi - i0, 0, 1), np.clip(fj - j0, 0, 1)
    i1, j1 = np.minimum(i0 + 1, ny - 1), np.minimum(j0 + 1, nx - 1)
    out = (values[..., i0, j0] * (1 - wi) * (1 - wj) + values[..., i0, j1] * (1 - wi) * wj
           + values[..., i1, j0] * wi * (1 - wj) + values[..., i1, j1] * wi * wj)
    return np.where(inside, out, np.nan)


def x_axis_bearing_deg(lat2: np.ndarray, lon2: np.ndarray) -> np.ndarray:
    """Bearing (deg clockwise from true north) of the grid's x axis at every node."""
    dlon = np.gradient(np.unwrap(np.deg2rad(lon2), axis=1), axis=1)
    dlat = np.gradient(np.deg2rad(lat2), axis=1)
    return np.rad2deg(np.arctan2(dlon * np.cos(np.deg2rad(lat2)), dlat))


def grid_to_earth(u: np.ndarray, v: np.ndarray, bearing_deg: np.ndarray
                  ) -> tuple[np.ndarray, np.ndarray]:
    """Grid-relative (x, y) components -> (east, north), for a conformal grid whose x axis
    points at `bearing_deg` (the y axis 90 deg to its left)."""
    a = np.deg2rad(bearing_deg)
    return u * np.sin(a) - v * np.cos(a), u * np.cos(a) + v * np.sin(a)


def regrid_projected(ds: xr.Dataset, where: str,
                     grid_relative: tuple[tuple[str, str], ...] = ()) -> xr.Dataset:
    """Regular latitude/longitude dataset from one on a projected (y, x) grid; the variable
    pairs in `grid_relative` are rotated from grid to east/north first."""
    from pyproj import Transformer

    lat2 = ds["latitude"].values.astype(np.float64)
    lon2 = ds["longitude"].values.astype(np.float64)
    ydim, xdim = ds["latitude"].dims
    crs = _crs(ds, where)
    fwd = Transformer.from_crs("EPSG:4326", crs, always_xy=True)
    x, y = fwd.transform(lon2, lat2)
    m = _affine_fit(np.asarray(x), np.asarray(y), where)
    lat_t, lon_t = _target_axes(lat2, lon2)
    lo, la = np.meshgrid(lon_t, lat_t)
    xt, yt = fwd.transform(((lo + 180.0) % 360.0) - 180.0, la)
    pts = np.column_stack([np.ravel(xt), np.ravel(yt), np.ones(lo.size)]) @ m
    fi, fj = pts[:, 0], pts[:, 1]
    bearing = x_axis_bearing_deg(lat2, lon2)
    data = {n: ds[n] for n in ds.data_vars if ds[n].dims[-2:] == (ydim, xdim)}
    arrays = {n: da.values.astype(np.float64) for n, da in data.items()}
    for un, vn in grid_relative:
        if un in arrays and vn in arrays:
            arrays[un], arrays[vn] = grid_to_earth(arrays[un], arrays[vn], bearing)
    out = {}
    for n, da in data.items():
        vals = _bilinear(arrays[n], fi, fj).reshape(*arrays[n].shape[:-2], *lo.shape)
        out[n] = ((*da.dims[:-2], "latitude", "longitude"), vals.astype(np.float32), da.attrs)
    coords = {k: c for k, c in ds.coords.items()
              if ydim not in c.dims and xdim not in c.dims and k not in ("latitude", "longitude")}
    coords.update(latitude=lat_t, longitude=lon_t)
    res = xr.Dataset(out, coords=coords, attrs=dict(ds.attrs))
    res.attrs["regridded_from"] = (f"{_label(ds)} {lat2.shape[1]} x {lat2.shape[0]} grid "
                                   f"regridded to {lat_t[1] - lat_t[0]:g} deg lat/lon"
                                   + (" (winds turned from grid to east/north)"
                                      if grid_relative else ""))
    return res
