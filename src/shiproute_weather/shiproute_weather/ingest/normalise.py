"""Turn a raw provider dataset (any supported naming convention) into the canonical dataset."""

from __future__ import annotations

import re

import numpy as np
import xarray as xr

from ..contract import canonical as cv
from ..contract.members import MEMBER_DIM, MEMBER_LABEL, check_unique_labels
from ..contract.timefmt import canonical_iso
from ..contract.units import si_factor
from ..errors import GridError, MissingVariableError
from ..physics.spectral import to_tm01_factor
from ..wire.slices import snap_grid
from .coords import (
    ascending_latitude,
    make_regular_lonlat,
    normalise_longitude,
    regular_axes,
    rename_coords,
    require_monotonic,
    utc_naive_times,
)
from .namemap import (
    CURRENT_DIR_NAMES,
    CURRENT_SPEED_NAMES,
    WIND_DIR_NAMES,
    WIND_SPEED_NAMES,
    Mapping,
    lookup,
)
from .outliers import mask_outliers

_DIMS = ("time", "latitude", "longitude")
_EXPECTED = ("wind (u10/v10, UGRD/VGRD, eastward_wind...), waves (swh, HTSGW, VHM0, "
             "sea_surface_wave_significant_height...) or currents (uo/vo, utotal/vtotal...)")


def _units(da: xr.DataArray) -> str | None:
    return da.attrs.get("units") or da.attrs.get("GRIB_units")


#: dimensions that hold ensemble members (GRIB `number`, CF `realization`, ...)
MEMBER_DIMS = ("number", "realization", "member", "ensemble", "ens", "member_id")
#: the height of the wind the canonical dataset holds [m]
WIND_HEIGHT_M = 10.0


def _pick_level(da: xr.DataArray, d: str, where: str) -> xr.DataArray:
    """Reduce one level dimension: the 10 m height, the shallowest depth, the first partition
    of an ordered sequence; a level dim of any other kind must have a single value."""
    name = d.lower()
    values = da[d].values if d in da.coords else None
    if name.startswith(("height", "heightaboveground")) and values is not None:
        k = int(np.argmin(np.abs(values.astype(np.float64) - WIND_HEIGHT_M)))
        if abs(float(values[k]) - WIND_HEIGHT_M) > 0.5:
            raise GridError(where, f"variable {da.name!r} has heights {list(values)} on "
                                   f"{d!r}; no {WIND_HEIGHT_M:g} m level")
        return da.isel({d: k}, drop=True)
    if name.startswith("depth") and values is not None:
        return da.isel({d: int(np.argmin(np.abs(values.astype(np.float64))))}, drop=True)
    if da.sizes[d] == 1 or "sequence" in name or name.startswith(("partition", "swell")):
        return da.isel({d: 0}, drop=True)
    raise GridError(where, f"variable {da.name!r} has a dimension {d!r} of "
                           f"{da.sizes[d]} values that is neither time, latitude, longitude, "
                           "height, depth nor ensemble member")


def _surface(da: xr.DataArray, where: str) -> xr.DataArray:
    """Level dims reduced (10 m wind, surface waves and currents); a member dim is kept first."""
    for d in [d for d in da.dims if d not in _DIMS and d not in MEMBER_DIMS]:
        da = _pick_level(da, str(d), where)
    members = [d for d in da.dims if d in MEMBER_DIMS]
    if len(members) > 1:
        raise GridError(where, f"variable {da.name!r} has several member dims {members}")
    if members:
        da = da.rename({members[0]: "member"})
        if da.sizes["member"] == 1:
            da = da.isel(member=0, drop=True)
    keep = (*_DIMS, "member")
    da = da.drop_vars([c for c in da.coords if c not in keep], errors="ignore")
    order = ("member", *_DIMS) if "member" in da.dims else _DIMS
    return da.transpose(*order)


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


def mapped_variables(raw: xr.Dataset) -> set[str]:
    """Canonical variables a raw dataset's names map to (names only; nothing is read)."""
    found = {m.canonical for _, m in _choose(raw).values()}
    for sp, dr, std_sp, std_dr, u in ((WIND_SPEED_NAMES, WIND_DIR_NAMES, "wind_speed",
                                       "wind_from_direction", cv.WIND_U),):
        if _find_named(raw, sp, std_sp) and _find_named(raw, dr, std_dr):
            found.add(u)
    return found


def _find_named(ds: xr.Dataset, names: tuple[str, ...], standard: str) -> str | None:
    for n in ds.data_vars:
        if str(n).lower() in names or ds[n].attrs.get("standard_name") == standard:
            return str(n)
    return None


def _convert(da: xr.DataArray, m: Mapping, where: str) -> tuple[np.ndarray, str]:
    """Values in canonical units and conventions (a member axis first, if any), and the
    conversion applied in words ('' when none)."""
    spec = cv.VARIABLES[m.canonical]
    vals = da.values if da.dims == _DIMS else _surface(da, where).values
    done = []
    if m.period_kind == "fp":  # peak frequency [Hz] -> peak period [s]
        f_hz = vals.astype(np.float64) * si_factor(_units(da), "s-1", where, str(da.name))
        with np.errstate(divide="ignore", invalid="ignore"):
            vals = np.where(f_hz > 0.0, 1.0 / f_hz, np.nan)
        da = da.assign_attrs(units="s")
        done.append(f"{da.name} peak frequency -> Tp = 1/fp")
    factor = si_factor(_units(da), spec.units, where, str(da.name))
    if factor != 1.0:
        done.append(f"{da.name} [{_units(da)}] x {factor:.6g} -> {spec.units}")
    if spec.units == "s" and m.period_kind != "tm01":
        k = to_tm01_factor("tp" if m.period_kind == "fp" else m.period_kind)
        factor *= k
        kind = {"tp": "peak period Tp", "fp": "peak period Tp", "tm02": "Tm02",
                "tm_10": "Tm-1,0"}[m.period_kind]
        done.append(f"{da.name} {kind} x {k:.3f} -> Tm01 (JONSWAP gamma 3.3 ratio)")
    if factor != 1.0 or vals.dtype != np.float32:
        vals = vals.astype(np.float64) * factor
    if spec.units == "degree":
        lo, hi = np.fmin.reduce(vals, axis=None), np.fmax.reduce(vals, axis=None)  # skip NaN
        if m.going_to or lo < 0.0 or hi >= 360.0:
            vals = (vals.astype(np.float64) + (180.0 if m.going_to else 0.0)) % 360.0
        if m.going_to:
            done.append(f"{da.name} 'going to' + 180 deg -> 'coming from'")
    return vals, "; ".join(done)


def _speed_dir_pairs(ds: xr.Dataset, out: dict[str, np.ndarray], where: str,
                     record: dict[str, dict[str, str]]) -> None:
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
        speed = _surface(ds[s], where).values.astype(np.float64)
        speed = speed * si_factor(_units(ds[s]), "m s-1", where, s)
        rad = np.deg2rad(_surface(ds[d], where).values.astype(np.float64)
                         * si_factor(_units(ds[d]), "degree", where, d))
        out[u_name] = sign * speed * np.sin(rad)
        out[v_name] = sign * speed * np.cos(rad)
        conv = f"{s} speed + {d} direction -> components"
        record[u_name] = {"source_variable": f"{s}+{d}", "conversion": conv}
        record[v_name] = {"source_variable": f"{s}+{d}", "conversion": conv}


def _slug(text: str) -> str:
    return re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-")[:40] or "forecast"


def _label(value: object) -> str:
    """A member number as a label: 3.0 -> '3', anything else as written."""
    if isinstance(value, float) and value.is_integer():
        return str(int(value))
    return str(value)


def _member_axis(out: dict[str, np.ndarray], member_values: np.ndarray | None,
                 member_dim: str, where: str) -> tuple[dict[str, np.ndarray], list[str], str]:
    """Fields with a member axis kept whole: (fields, member labels, statement). A field
    without members beside member fields is the same in every member (broadcast, stated)."""
    if not any(v.ndim == 4 for v in out.values()):
        return out, [], ""
    n = next(v.shape[0] for v in out.values() if v.ndim == 4)
    counts = {c: v.shape[0] for c, v in out.items() if v.ndim == 4}
    if len(set(counts.values())) > 1:
        raise GridError(where, f"fields have different member counts {counts}")
    labels = ([_label(x) for x in np.asarray(member_values).tolist()]
              if member_values is not None else [str(k) for k in range(n)])
    check_unique_labels(labels, f"{where} ({member_dim})")
    shared = [c for c, v in out.items() if v.ndim != 4]
    full = {c: (v if v.ndim == 4 else np.repeat(v[None], n, axis=0)) for c, v in out.items()}
    said = f"{n} members kept from dimension {member_dim!r} (labels {', '.join(labels[:8])}" \
           f"{', ...' if n > 8 else ''})"
    if shared:
        said += f"; {', '.join(shared)} have no members and are the same in every member"
    return full, labels, said


def _member_info(ds: xr.Dataset, chosen: dict[str, tuple[str, Mapping]]
                 ) -> tuple[np.ndarray | None, str]:
    for n, _ in chosen.values():
        for d in ds[n].dims:
            if d in MEMBER_DIMS and ds.sizes[d] > 1:
                return (ds[d].values if d in ds.coords else np.arange(ds.sizes[d])), str(d)
    return None, ""


def member_axis(raw: xr.Dataset, where: str) -> tuple[str, list[str]]:
    """(raw member dimension, member labels as `to_canonical` gives them) of a raw dataset, read
    from names and coordinates only; ("", []) when it has no member dimension of > 1 member."""
    ds = rename_coords(raw, where)
    values, dim = _member_info(ds, _choose(ds))
    if values is None:
        return "", []
    labels = [_label(x) for x in np.asarray(values).tolist()]
    check_unique_labels(labels, f"{where} ({dim})")
    return dim, labels


def to_canonical(raw: xr.Dataset, where: str) -> xr.Dataset:
    """Canonical dataset from a raw one: names, SI units, directions, grid, UTC times.

    Every canonical variable records its `source_file`, `source_variable` and `conversion`;
    impossible values are masked (see `outliers`); an ensemble keeps every member: its
    variables get a leading `member` dim (`contract.members`), labelled by the source's
    member numbers (GRIB `number`, CF `realization`, ...).
    """
    ds = rename_coords(raw, where)
    ds = make_regular_lonlat(ds, where)
    require_monotonic(ds, where)
    chosen = _choose(ds)
    out: dict[str, np.ndarray] = {}
    record: dict[str, dict[str, str]] = {}
    for c, (n, m) in chosen.items():
        out[c], conv = _convert(ds[n], m, where)
        record[c] = {"source_variable": n, "conversion": conv}
    _speed_dir_pairs(ds, out, where, record)
    if not out:
        raise MissingVariableError(where, "any forecast variable", _EXPECTED)
    member_values, member_dim = _member_info(ds, chosen)
    out, labels, used = _member_axis(out, member_values, member_dim, where)
    dims = (MEMBER_DIM, *_DIMS) if labels else _DIMS
    data: dict[str, tuple[tuple[str, ...], np.ndarray]] = {
        c: (dims, out[c].astype(np.float32, copy=False)) for c in cv.CANONICAL_ORDER if c in out}
    coords: dict[str, object] = {"time": ds["time"].values, "latitude": ds["latitude"].values,
                                 "longitude": ds["longitude"].values}
    if labels:
        coords[MEMBER_DIM] = np.arange(len(labels), dtype=np.int64)
        coords[MEMBER_LABEL] = (MEMBER_DIM, np.array(labels, dtype=object))
    res = xr.Dataset(data, coords=coords)
    res = utc_naive_times(ascending_latitude(normalise_longitude(res, where)), where)
    res, dropped = regular_axes(res, where)
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
    res.attrs = {"forecast_reference_time": ref, "source": source, "cycle_id": cycle,
                 "source_files": where}
    if used:
        res.attrs["ensemble"] = used
        res.attrs["member_kind"] = "ensemble"
    if dropped or "regridded_from" in ds.attrs:
        res.attrs["grid_notes"] = "; ".join([*dropped, *([str(ds.attrs["regridded_from"])]
                                                         if "regridded_from" in ds.attrs else [])])
    for c, rec in record.items():
        if c in res:
            res[c].attrs.update(source_file=where, **rec)
    mask_outliers(res, where)
    return cv.annotate(res)
