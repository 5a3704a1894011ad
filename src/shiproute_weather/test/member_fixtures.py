"""Ensemble and multi-model forecast files for tests, written from real GRIB messages.

Debian `python-grib-doc` ships a real NCEP GFS 2.5 deg GRIB2 (10 m wind, 2011-01-15 12 UTC +
120 h) and a real ECMWF TIGGE GRIB (10 m wind). Ensembles are made from them the way ECMWF and
NCEP encode members: product definition template 4.1 (`productDefinitionTemplateNumber` 1),
`typeOfEnsembleForecast` (1 control, 3 perturbed), `perturbationNumber` and
`numberOfForecastsInEnsemble`, `typeOfProcessedData` 3 (control) / 4 (perturbed), with the
eastward wind of member k shifted by a known amount.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np
import xarray as xr
from shiproute_weather.contract import canonical as cv

EXAMPLES = Path("/usr/share/doc/python-grib-doc/examples")
GFS = EXAMPLES / "gfs.t12z.pgrbf120.2p5deg.grib2"
TIGGE = EXAMPLES / "ecmwf_tigge.grb"


_GRID_KEYS = ("Ni", "Nj", "latitudeOfFirstGridPointInDegrees",
              "latitudeOfLastGridPointInDegrees", "longitudeOfFirstGridPointInDegrees",
              "longitudeOfLastGridPointInDegrees", "iDirectionIncrementInDegrees",
              "jDirectionIncrementInDegrees", "iScansNegatively", "jScansPositively",
              "jPointsAreConsecutive", "dataDate", "dataTime", "centre")


def _wind_fields(path: Path) -> list[tuple[str, dict[str, object], np.ndarray]]:
    """(shortName, grid/time keys, values) of every 10 m wind field of a regular lat/lon GRIB
    file (also when u and v share one message); handles are released as they are read."""
    import eccodes

    out = []
    eccodes.codes_grib_multi_support_on()
    try:
        with path.open("rb") as f:
            while (h := eccodes.codes_grib_new_from_file(f)) is not None:
                try:
                    short = str(eccodes.codes_get(h, "shortName"))
                    level = int(eccodes.codes_get(h, "level"))
                    tol = str(eccodes.codes_get(h, "typeOfLevel"))
                    name = {"u": "10u", "v": "10v"}.get(short, short)
                    if name in ("10u", "10v") and tol == "heightAboveGround" and level == 10:
                        keys = {k: eccodes.codes_get(h, k) for k in _GRID_KEYS}
                        keys["step"] = int(eccodes.codes_get(h, "endStep"))
                        out.append((name, keys, eccodes.codes_get_values(h).copy()))
                finally:
                    eccodes.codes_release(h)
            eccodes.codes_grib_multi_support_reset_file(f)
    finally:
        eccodes.codes_grib_multi_support_off()
    return out


def ensemble_grib2(path: Path, u_shift_m_s: Sequence[float], source: Path = GFS) -> Path:
    """A GRIB2 ensemble of the real 10 m wind of `source` (its grid, times and values in fresh
    GRIB2 messages): member k (0 = control) has the eastward wind + u_shift_m_s[k]."""
    import eccodes

    n = len(u_shift_m_s)
    parts = []
    seen = set()
    for name, keys, values in _wind_fields(source):
        if (name, keys["step"]) in seen:  # one field per name and step
            continue
        seen.add((name, keys["step"]))
        for k, du in enumerate(u_shift_m_s):
            m = eccodes.codes_grib_new_from_samples("regular_ll_sfc_grib2")
            try:
                for key, value in keys.items():
                    eccodes.codes_set(m, key, value)
                eccodes.codes_set(m, "productDefinitionTemplateNumber", 1)
                eccodes.codes_set(m, "typeOfEnsembleForecast", 3 if k else 1)
                # control / perturbed forecast (code table 1.4): separate hypercubes
                eccodes.codes_set(m, "typeOfProcessedData", 4 if k else 3)
                eccodes.codes_set(m, "perturbationNumber", k)
                eccodes.codes_set(m, "numberOfForecastsInEnsemble", n)
                eccodes.codes_set_string(m, "shortName", name)
                eccodes.codes_set_values(m, values + (du if name == "10u" else 0.0))
                parts.append(bytes(eccodes.codes_get_message(m)))
            finally:
                eccodes.codes_release(m)
    path.write_bytes(b"".join(parts))
    return path


def realization_netcdf(ds: xr.Dataset, path: Path, u_shift_m_s: Sequence[float]) -> Path:
    """A CF NetCDF with a `realization` dimension (time, realization, lat, lon) holding the
    deterministic canonical `ds` with the eastward wind + u_shift_m_s[k] in realization k,
    under ECMWF names (u10, v10, swh where present)."""
    names = {cv.WIND_U: "u10", cv.WIND_V: "v10", cv.WAVE_HS: "swh"}
    shifts = np.asarray(u_shift_m_s, dtype=np.float32)
    data = {}
    for canon, raw in names.items():
        if canon not in ds:
            continue
        a = ds[canon].values.astype(np.float32)
        stack = np.stack([a + (s if canon == cv.WIND_U else 0.0) for s in shifts], axis=1)
        data[raw] = (("time", "realization", "latitude", "longitude"), stack,
                     {"units": cv.VARIABLES[canon].units})
    out = xr.Dataset(data, coords={"time": ds["time"].values,
                                   "realization": np.arange(shifts.size, dtype=np.int32),
                                   "latitude": ds["latitude"].values,
                                   "longitude": ds["longitude"].values},
                     attrs={"source": "realization test ensemble"})
    out["realization"].attrs["standard_name"] = "realization"
    enc = {n: {"zlib": True, "dtype": "float32", "_FillValue": np.float32(np.nan)}
           for n in out.data_vars}
    enc["time"] = {"units": "hours since 2000-01-01 00:00:00", "dtype": "float64"}
    out.to_netcdf(path, encoding=enc)
    return path


def perturbed_members(ds: xr.Dataset, n: int, seed: int = 7) -> xr.Dataset:
    """An n-member ensemble dataset from a deterministic one: member 0 as it is, member k with
    the wind scaled by 1 + 0.1 N(0,1) and Hs by the square of that factor (Hs ~ U^2 for a wind
    sea), directions unchanged: a spread like a short-range ensemble's, bounded to the
    contract's physical ranges."""
    from shiproute_weather.contract.members import stack_members

    rng = np.random.default_rng(seed)
    members = [ds]
    for _ in range(1, n):
        f = float(np.clip(1.0 + 0.1 * rng.standard_normal(), 0.7, 1.3))
        m = ds.copy(deep=True)
        for name in (cv.WIND_U, cv.WIND_V):
            if name in m:
                m[name].values *= f
        for name in (cv.WAVE_HS, cv.WIND_WAVE_HS):
            if name in m:
                m[name].values = np.minimum(m[name].values * f * f, 29.0)
        members.append(m)
    return stack_members(members, [str(k) for k in range(n)], kind="ensemble")
