"""Put several canonical datasets (wind, waves, currents from different models) on one grid."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import xarray as xr

from ..contract import canonical as cv
from ..contract.members import MEMBER_DIM, MEMBER_LABEL, member_labels, select_member
from ..errors import GridError
from ..wire.slices import snap_grid
from .regrid import regrid

#: a field of a file with fewer valid times than the cycle's is held this long beyond its own
#: span [h] (the planner's own persistence bound beyond the whole cycle is the same default)
PERSISTENCE_H = 24.0


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
    from ..sampling.sampler import ForecastSampler  # numba is loaded only when resampling is needed

    sampler = ForecastSampler(ds)
    t_s = times.astype("datetime64[ns]").astype(np.int64).astype(np.float64) / 1e9
    tt, la, lo = np.meshgrid(t_s, latitudes_deg, longitudes_deg, indexing="ij")
    values = sampler.sample(lo, la, tt)
    out = xr.Dataset(
        {n: (("time", "latitude", "longitude"), v.astype(np.float32)) for n, v in values.items()},
        coords={"time": times, "latitude": latitudes_deg, "longitude": longitudes_deg},
        attrs=dict(ds.attrs))
    return cv.annotate(out)


def _lon_overlap(a: np.ndarray, b: np.ndarray) -> bool:
    """Whether longitude ranges a and b (any 360-frame) intersect."""
    if a[-1] - a[0] + abs(a[1] - a[0] if a.size > 1 else 0) >= 360.0 - 1e-6:
        return True
    if b[-1] - b[0] + abs(b[1] - b[0] if b.size > 1 else 0) >= 360.0 - 1e-6:
        return True
    rel0 = (b[0] - a[0]) % 360.0
    rel1 = (a[0] - b[0]) % 360.0
    return rel0 <= a[-1] - a[0] + 1e-9 or rel1 <= b[-1] - b[0] + 1e-9


def check_overlap(base: xr.Dataset, d: xr.Dataset) -> None:
    """Refuse a file whose grid or valid times do not meet the cycle's first file at all."""
    where = str(d.attrs.get("source_files", d.attrs.get("cycle_id", "dataset")))
    target = str(base.attrs.get("source_files", base.attrs.get("cycle_id", "dataset")))
    la, lb = base["latitude"].values, d["latitude"].values
    if lb[-1] < la[0] or lb[0] > la[-1] or not _lon_overlap(base["longitude"].values,
                                                          d["longitude"].values):
        raise GridError(where, f"its grid ({lb[0]:g}..{lb[-1]:g} N, "
                               f"{d['longitude'].values[0]:g}..{d['longitude'].values[-1]:g} E) "
                               f"does not overlap the grid of {target}")
    ta, tb = base["time"].values, d["time"].values
    hold = np.timedelta64(int(PERSISTENCE_H * 3600), "s")
    if tb[-1] + hold < ta[0] or tb[0] - hold > ta[-1]:
        raise GridError(where, f"its valid times {_iso(tb[0])}..{_iso(tb[-1])} do not overlap "
                               f"those of {target} ({_iso(ta[0])}..{_iso(ta[-1])})")


def _iso(t: np.datetime64) -> str:
    return str(np.datetime_as_string(t, unit="m")) + "Z"


def _onto(d: xr.Dataset, names: list[str], base: xr.Dataset) -> xr.Dataset:
    """Variables `names` of `d` on the axes of `base`. At the cycle's valid times beyond `d`'s
    own span its edge fields are held for at most `PERSISTENCE_H` (stated in the field's
    `conversion`), then missing (NaN)."""
    times = base["time"].values
    if np.isin(times, d["time"].values).all():
        sub = d[names].sel(time=times)
        if _same_axes(sub, base):
            return sub
    out = regrid(d[names], base["latitude"].values.astype(np.float64),
                 base["longitude"].values.astype(np.float64), times)
    t0, t1 = d["time"].values[0], d["time"].values[-1]
    hold = np.timedelta64(int(PERSISTENCE_H * 3600), "s")
    outside = (times < t0 - hold) | (times > t1 + hold)
    held = ~outside & ((times < t0) | (times > t1))
    notes = [f"regridded (trilinear) onto the grid and valid times of "
             f"{base.attrs.get('source_files', 'the first file')}"]
    if held.any():
        notes.append(f"held (persistence, at most {PERSISTENCE_H:g} h) beyond its valid times "
                     f"{_iso(t0)} .. {_iso(t1)} at {int(held.sum())} of the cycle's times")
    if outside.any():
        notes.append(f"missing at {int(outside.sum())} of the cycle's times beyond that")
    for n in names:
        if outside.any():
            out[n].values[outside] = np.nan
        out[n].attrs.update({k: v for k, v in d[n].attrs.items() if k not in out[n].attrs})
        out[n].attrs["conversion"] = "; ".join(
            x for x in (str(d[n].attrs.get("conversion", "")), *notes) if x)
    return out


def onto(d: xr.Dataset, names: list[str], base: xr.Dataset) -> xr.Dataset:
    """Variables `names` of `d` on the axes of `base`, member by member when `d` has members
    (see `_onto`; `d`'s member dimension and labels are kept)."""
    if MEMBER_DIM not in d.dims:
        return _onto(d, names, base)
    per = [_onto(select_member(d, k), names, base) for k in range(d.sizes[MEMBER_DIM])]
    out = xr.concat(per, dim=MEMBER_DIM, combine_attrs="override")
    out = out.assign_coords({MEMBER_DIM: d[MEMBER_DIM].values,
                             MEMBER_LABEL: (MEMBER_DIM, list(member_labels(d)))})
    return out.transpose(MEMBER_DIM, "time", "latitude", "longitude")


def _members_broadcast(merged: dict[str, xr.DataArray], where: str
                       ) -> tuple[dict[str, xr.DataArray], str]:
    """Give every variable the member axis of the ones that have it (deterministic fields are
    the same in every member, stated); member counts of different files must agree."""
    counts = {n: a.sizes[MEMBER_DIM] for n, a in merged.items() if MEMBER_DIM in a.dims}
    if not counts:
        return merged, ""
    if len(set(counts.values())) > 1:
        raise GridError(where, f"member count mismatch between files: {counts}; an ensemble "
                               "cycle needs the same members in every file")
    ref = next(a for a in merged.values() if MEMBER_DIM in a.dims)
    n = ref.sizes[MEMBER_DIM]
    shared = [k for k, a in merged.items() if MEMBER_DIM not in a.dims]
    out = {}
    for k, a in merged.items():
        if MEMBER_DIM not in a.dims:
            a = xr.DataArray(np.repeat(a.values[None], n, axis=0),
                             dims=(MEMBER_DIM, *a.dims), attrs=a.attrs)
        out[k] = a.drop_vars([c for c in a.coords if c not in a.dims], errors="ignore")
    note = (f"{', '.join(shared)} have no members and are the same in every member"
            if shared else "")
    return out, note


def combine(datasets: Sequence[xr.Dataset], target: int | None = None) -> xr.Dataset:
    """Merge datasets onto the grid and valid times of one of them (default: the first with
    wind, else the first). Each variable keeps its source file; a variable from a file with
    a shorter span is missing (NaN) at the valid times beyond it. Earlier datasets win when
    two provide the same variable. A file whose grid or times miss the target's is refused."""
    if len(datasets) == 1:
        return datasets[0]
    if target is None:
        target = next((i for i, d in enumerate(datasets) if cv.WIND_U in d), 0)
    base = datasets[target]
    times = base["time"].values
    lat, lon = base["latitude"].values, base["longitude"].values
    merged: dict[str, xr.DataArray] = {}
    sources, files = [], []
    order = [target] + [i for i in range(len(datasets)) if i != target]
    for i in order:
        d = datasets[i]
        if i != target:
            check_overlap(base, d)
        sources.append(str(d.attrs.get("source", "")))
        files.append(str(d.attrs.get("source_files", "")))
        new = [n for n in cv.present_variables(d) if n not in merged]
        if not new:
            continue
        sub = d[new] if i == target else onto(d, new, base)
        merged.update({n: sub[n] for n in new})
    labelled = next((d for d in (datasets[i] for i in order) if MEMBER_DIM in d.dims), None)
    merged, shared_note = _members_broadcast(merged, ", ".join(
        str(d.attrs.get("source_files", "")) for d in datasets))
    ordered = {n: merged[n] for n in cv.CANONICAL_ORDER if n in merged}
    coords: dict[str, object] = {"time": times, "latitude": lat, "longitude": lon}
    if labelled is not None:
        coords[MEMBER_DIM] = np.arange(labelled.sizes[MEMBER_DIM], dtype=np.int64)
        coords[MEMBER_LABEL] = (MEMBER_DIM, list(member_labels(labelled)))
    out = xr.Dataset(ordered, coords=coords)
    out.attrs = {
        "forecast_reference_time": max(str(d.attrs["forecast_reference_time"])
                                       for d in datasets),
        "source": "+".join(dict.fromkeys(s for s in sources if s)),
        "cycle_id": str(base.attrs["cycle_id"]),
        "source_files": ", ".join(f for f in files if f),
    }
    for d in datasets:
        for key in ("ensemble", "member_kind"):
            if key in d.attrs:
                out.attrs[key] = d.attrs[key]
    if shared_note:
        out.attrs["ensemble"] = f"{out.attrs.get('ensemble', 'members')}; {shared_note}"
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
