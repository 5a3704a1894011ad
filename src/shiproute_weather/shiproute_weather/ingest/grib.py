"""Read the forecast variables of a GRIB1/GRIB2 file with cfgrib/eccodes (PyPI wheels).

A GRIB file may hold several hypercubes (levels, grids, steps); the messages are scanned first
and only the ones that map to canonical variables are opened, one cfgrib call per
(typeOfLevel, shortName) so unrelated hypercubes never conflict.
"""

from __future__ import annotations

import tempfile
import warnings
from pathlib import Path

import numpy as np
import xarray as xr

from ..errors import ForecastFileError
from .namemap import NAMES, WIND_DIR_NAMES, WIND_SPEED_NAMES

# shortName -> accepted (typeOfLevel, level or None for any); 10 m winds only
_WIND_LEVELS = (("heightAboveGround", 10), ("surface", None), ("meanSea", None))
_SPECIAL: dict[str, tuple[tuple[str, int | None], ...]] = {
    "10u": _WIND_LEVELS, "10v": _WIND_LEVELS, "u": (("heightAboveGround", 10),),
    "v": (("heightAboveGround", 10),), "10si": _WIND_LEVELS, "10wdir": _WIND_LEVELS,
}
_RENAME = {"u": "u10", "v": "v10", "10u": "u10", "10v": "v10", "10si": "ws", "10wdir": "wdir"}


def scan(path: Path) -> tuple[list[tuple[str, str, int]], list[bytes], str, set[str]]:
    """Every field's (shortName, typeOfLevel, level), the wanted fields as standalone GRIB
    messages, the originating centre, and the shortNames whose vector components are
    relative to the grid's axes (projected grids; flag uvRelativeToGrid).

    Multi-field messages (older NCEP files pack u and v in one message) are split into
    single-field messages. Raises ForecastFileError for a corrupt or truncated file.
    """
    import eccodes

    fields: list[tuple[str, str, int]] = []
    wanted: list[bytes] = []
    centre = ""
    grid_relative: set[str] = set()
    eccodes.codes_grib_multi_support_on()
    try:
        with path.open("rb") as f:
            try:
                while True:
                    h = eccodes.codes_grib_new_from_file(f)
                    if h is None:
                        break
                    try:
                        key = (str(eccodes.codes_get(h, "shortName")),
                               str(eccodes.codes_get(h, "typeOfLevel")),
                               int(eccodes.codes_get(h, "level")))
                        fields.append(key)
                        if _wanted(*key):
                            msg = bytes(eccodes.codes_get_message(h))
                            if not wanted or wanted[-1] != msg:  # u and v of one message
                                wanted.append(msg)
                            centre = centre or str(eccodes.codes_get(h, "centre"))
                            if _uv_relative_to_grid(h):
                                grid_relative.add(key[0])
                    finally:
                        eccodes.codes_release(h)
            finally:
                # a file given up half-way (truncated) must not leave ecCodes' multi-field
                # state to the next file read
                eccodes.codes_grib_multi_support_reset_file(f)
    except Exception as exc:
        raise ForecastFileError(str(path), f"corrupt or truncated GRIB ({exc})") from exc
    finally:
        eccodes.codes_grib_multi_support_off()
    if not fields:
        raise ForecastFileError(str(path), "no GRIB messages found")
    return fields, wanted, centre, grid_relative


def _uv_relative_to_grid(h: object) -> bool:
    """Vector components along the grid's axes (flag table 3.3 / GRIB1 table 7, bit 5 =
    0x08 of resolutionAndComponentFlags), on a grid whose axes are not east/north."""
    import eccodes

    if str(eccodes.codes_get(h, "gridType")) in ("regular_ll", "reduced_ll", "regular_gg",
                                                 "reduced_gg"):
        return False
    if eccodes.codes_is_defined(h, "resolutionAndComponentFlags"):
        return bool(int(eccodes.codes_get(h, "resolutionAndComponentFlags")) & 0x08)
    return False


def _wanted(short: str, tol: str, level: int) -> bool:
    if short in _SPECIAL:
        return any(tol == t and (lv is None or lv == level) for t, lv in _SPECIAL[short])
    key = short.lower()
    if key in ("u10", "v10") or key in WIND_SPEED_NAMES or key in WIND_DIR_NAMES:
        return tol in ("heightAboveGround", "surface", "meanSea") and (
            tol != "heightAboveGround" or level == 10)
    if key in NAMES:
        # swell partitions: keep the first ordered sequence only (primary swell)
        return not (tol == "orderedSequenceData" and level != 1)
    return False


def open_grib(path: Path) -> xr.Dataset:
    """Mapped variables of a GRIB file as one raw dataset (cfgrib coordinate names).

    The wanted messages are copied into a temporary file first so cfgrib indexes only them
    (a full GFS file has hundreds of unrelated fields).
    """
    import cfgrib

    fields, wanted, centre, grid_relative = scan(path)
    if not wanted:
        found = sorted({m[0] for m in fields})
        raise ForecastFileError(str(path), "no forecast variable found; GRIB shortNames "
                                f"{found[:20]} include none of wind/waves/currents")
    parts: list[xr.Dataset] = []
    with tempfile.TemporaryDirectory(prefix="shiproute-grib-") as tmp:
        sub = Path(tmp) / "wanted.grib"
        sub.write_bytes(b"".join(wanted))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            try:
                dss = cfgrib.open_datasets(str(sub), backend_kwargs={"indexpath": ""})
            except Exception as exc:
                raise ForecastFileError(str(path), f"cfgrib cannot decode it ({exc})") from exc
            for ds in dss:
                parts.extend(_variables(ds, grid_relative))
    if not parts:
        raise ForecastFileError(str(path), "no 10 m wind, wave or current field decoded")
    merged = _merge(parts, path)
    merged.attrs["source"] = f"GRIB centre {centre}"
    return merged


def _variables(ds: xr.Dataset,
               grid_relative: set[str] | frozenset[str] = frozenset()) -> list[xr.Dataset]:
    """Each wanted variable of one cfgrib hypercube, level dims reduced, names harmonised."""
    out = []
    for name in list(ds.data_vars):
        da = ds[name].load()
        short = str(da.attrs.get("GRIB_shortName", name))
        if short in grid_relative:
            da.attrs["GRIB_uvRelativeToGrid"] = 1
        tol = str(da.attrs.get("GRIB_typeOfLevel", ""))
        if not (_wanted(short, tol, 10 if tol == "heightAboveGround" else 1)
                or _wanted(str(name), tol, 10 if tol == "heightAboveGround" else 1)):
            continue
        # an ensemble's `number` dim is kept: the canonical dataset carries the members
        if tol in da.dims:
            levels = da[tol].values
            pick = int(np.argmin(np.abs(levels - (10 if tol == "heightAboveGround" else 1))))
            da = da.isel({tol: pick}, drop=True)
        da = da.drop_vars([c for c in da.coords if c == tol], errors="ignore")
        out.append(da.rename(_RENAME.get(short, str(name))).to_dataset())
    return out


def _flatten_runs(p: xr.Dataset) -> xr.Dataset:
    """(time, step) hypercubes (several model runs) -> one valid-time axis; where runs
    overlap, the latest run wins."""
    name = next(iter(p.data_vars))
    da = p[name].transpose("time", "step", ...)
    vt = p["valid_time"].transpose("time", "step").values.reshape(-1)
    ref = np.repeat(p["time"].values, p.sizes["step"])
    order = np.lexsort((ref, vt))
    vt_s = vt[order]
    keep = order[np.r_[vt_s[1:] != vt_s[:-1], True]]
    values = da.values.reshape(-1, *da.shape[2:])[keep]
    rest = da.dims[2:]
    out = xr.DataArray(values, dims=("valid_time", *rest), attrs=da.attrs,
                       coords={"valid_time": vt[keep], **{d: p[d] for d in rest if d in p.coords}})
    return out.to_dataset(name=name).assign_coords(reference_time=ref.min())


def _join_members(parts: list[xr.Dataset]) -> list[xr.Dataset]:
    """Parts of one variable split by member joined along `number`: ECMWF and NCEP encode the
    control ('cf') and the perturbed members ('pf') as separate hypercubes, and every member
    must be kept. Parts of a variable whose numbers repeat are left as they are."""
    by_name: dict[str, list[xr.Dataset]] = {}
    for p in parts:
        by_name.setdefault(str(next(iter(p.data_vars))), []).append(p)
    out: list[xr.Dataset] = []
    for group in by_name.values():
        if len(group) < 2 or any("number" not in p.coords for p in group):
            out.extend(group)
            continue
        expanded = [p if "number" in p.dims else p.expand_dims("number") for p in group]
        numbers = np.concatenate([np.atleast_1d(p["number"].values) for p in expanded])
        if len(set(numbers.tolist())) != numbers.size:
            out.extend(group)
            continue
        joined = xr.concat(expanded, dim="number", join="outer", coords="minimal",
                           compat="override", combine_attrs="drop_conflicts")
        out.append(joined.sortby("number"))
    return out


def _merge(parts: list[xr.Dataset], path: Path) -> xr.Dataset:
    """Merge per-variable datasets (members of one variable joined); forecast steps become
    valid times."""
    fixed = []
    for p in _join_members(parts):
        p = p.drop_vars([c for c in ("surface", "meanSea", "heightAboveGround",
                                     "orderedSequenceData") if c in p.coords], errors="ignore")
        if "step" in p.dims and "time" in p.dims:
            p = _flatten_runs(p)
        if "step" in p.dims:
            p = p.swap_dims({"step": "valid_time"}).drop_vars(["step"], errors="ignore")
        elif "time" in p.dims and "valid_time" in p.coords and p["valid_time"].dims == ("time",):
            p = p.assign_coords(reference_time=p["time"].min()).swap_dims(
                {"time": "valid_time"}).drop_vars("time")
        if "time" in p.coords and "time" not in p.dims:
            p = p.rename({"time": "reference_time"})
        p = p.drop_vars(["step"], errors="ignore")
        if "valid_time" not in p.dims:
            p = p.expand_dims("valid_time") if "valid_time" in p.coords else p
        fixed.append(p.rename({"valid_time": "time"}))
    try:
        ds = xr.merge(fixed, compat="override", join="outer", combine_attrs="drop_conflicts")
    except Exception as exc:
        raise ForecastFileError(str(path), f"GRIB hypercubes cannot be merged ({exc})") from exc
    if "reference_time" in ds.coords:
        ref = np.atleast_1d(ds["reference_time"].values).min()
        ds = ds.drop_vars("reference_time")
        ds.attrs["forecast_reference_time"] = str(np.datetime_as_string(ref, unit="s")) + "Z"
    return ds
