"""Put several canonical datasets (wind, waves, currents from different models) on one grid."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import xarray as xr

from . import canonical as cv
from .errors import GridError
from .slices import snap_grid


@dataclass(frozen=True)
class Box:
    """Region of interest; lon_max_deg may exceed 180 (or lon_min be < -180 +360) to span 180."""

    lat_min_deg: float
    lat_max_deg: float
    lon_min_deg: float
    lon_max_deg: float


def _same_axes(a: xr.Dataset, b: xr.Dataset) -> bool:
    return (a.sizes == b.sizes and np.array_equal(a["time"].values, b["time"].values)
            and np.allclose(a["latitude"].values, b["latitude"].values)
            and np.allclose(a["longitude"].values, b["longitude"].values))


def resample(ds: xr.Dataset, latitudes_deg: np.ndarray, longitudes_deg: np.ndarray,
             times: np.ndarray) -> xr.Dataset:
    """Interpolate a canonical dataset onto other axes (trilinear; directions as vectors)."""
    from .sampling import ForecastSampler  # numba is loaded only when resampling is needed

    sampler = ForecastSampler(ds)
    t_s = times.astype("datetime64[ns]").astype(np.int64).astype(np.float64) / 1e9
    tt, la, lo = np.meshgrid(t_s, latitudes_deg, longitudes_deg, indexing="ij")
    values = sampler.sample(lo, la, tt)
    out = xr.Dataset(
        {n: (("time", "latitude", "longitude"), v.astype(np.float32)) for n, v in values.items()},
        coords={"time": times, "latitude": latitudes_deg, "longitude": longitudes_deg},
        attrs=dict(ds.attrs))
    return cv.annotate(out)


def combine(datasets: Sequence[xr.Dataset], target: int | None = None) -> xr.Dataset:
    """Merge datasets onto the grid and valid times of one of them (default: the first with
    wind, else the first), restricted to the time span all of them cover. Earlier datasets
    win when two provide the same variable."""
    if len(datasets) == 1:
        return datasets[0]
    if target is None:
        target = next((i for i, d in enumerate(datasets) if cv.WIND_U in d), 0)
    base = datasets[target]
    t0 = max(d["time"].values[0] for d in datasets)
    t1 = min(d["time"].values[-1] for d in datasets)
    times = base["time"].values
    times = times[(times >= t0) & (times <= t1)]
    if times.size == 0:
        raise GridError("combined forecast", "the files share no common valid-time span")
    lat, lon = base["latitude"].values, base["longitude"].values
    merged: dict[str, xr.DataArray] = {}
    sources = []
    order = [target] + [i for i in range(len(datasets)) if i != target]
    for i in order:
        d = datasets[i]
        sources.append(str(d.attrs.get("source", "")))
        new = [n for n in cv.present_variables(d) if n not in merged]
        if not new:
            continue
        sub = d[new].sel(time=times) if np.isin(times, d["time"].values).all() else None
        if sub is None or not _same_axes(sub, base.sel(time=times)):
            sub = resample(d[new], lat, lon, times)
        merged.update({n: sub[n] for n in new})
    ordered = {n: merged[n] for n in cv.CANONICAL_ORDER if n in merged}
    out = xr.Dataset(ordered, coords={"time": times, "latitude": lat, "longitude": lon})
    out.attrs = {
        "forecast_reference_time": max(str(d.attrs["forecast_reference_time"])
                                       for d in datasets),
        "source": "+".join(dict.fromkeys(s for s in sources if s)),
        "cycle_id": str(base.attrs["cycle_id"]),
    }
    return cv.annotate(out)


def subset(ds: xr.Dataset, box: Box, stride: int = 1) -> xr.Dataset:
    """Cut a canonical dataset to a box (wrapping longitudes into the box's frame), keeping
    every `stride`-th row/column. Longitudes of the result start at or after lon_min_deg."""
    lat = ds["latitude"].values
    rows = np.nonzero((lat >= box.lat_min_deg - 1e-9) & (lat <= box.lat_max_deg + 1e-9))[0]
    lon = ds["longitude"].values
    rel = (lon - box.lon_min_deg) % 360.0
    cols = np.nonzero(rel <= box.lon_max_deg - box.lon_min_deg + 1e-9)[0]
    if rows.size == 0 or cols.size == 0:
        raise GridError(str(ds.attrs.get("cycle_id", "dataset")),
                        f"region {box} does not intersect the forecast grid")
    cols = cols[np.argsort(rel[cols], kind="stable")]
    out = ds.isel(latitude=rows[::stride], longitude=cols[::stride])
    out = snap_grid(out.assign_coords(longitude=box.lon_min_deg + rel[cols[::stride]]))
    cv.grid_of(out, str(ds.attrs.get("cycle_id", "dataset")))
    return out
