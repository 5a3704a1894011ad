"""What a loaded forecast holds and how it was made, for load reports and plan statements.

The record lives in the canonical dataset itself (variable attributes `source_file`,
`source_variable`, `conversion`, `masked_outliers`; dataset attributes `source_files`,
`waves_estimated`, `ensemble`), so it survives combining and subsetting; this module reads it.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from . import canonical as cv

_WAVES = (cv.WAVE_HS, cv.WIND_WAVE_HS, cv.SWELL_HS)
_GROUPS = {"wind": (cv.WIND_U, cv.WIND_V), "waves": _WAVES,
           "currents": (cv.CURRENT_U, cv.CURRENT_V)}


def field_record(ds: Any) -> dict[str, dict[str, Any]]:
    """Per canonical field: source file, source variable, conversion, masked value count."""
    out: dict[str, dict[str, Any]] = {}
    for n in cv.present_variables(ds):
        a = ds[n].attrs
        out[n] = {"source_file": str(a.get("source_file", ds.attrs.get("source_files", ""))),
                  "source_variable": str(a.get("source_variable", n)),
                  "conversion": str(a.get("conversion", "")),
                  "masked_outliers": int(a.get("masked_outliers", 0))}
    return out


def valid_range(ds: Any) -> tuple[str, str]:
    """First and last valid time (ISO 8601 UTC)."""
    t = ds["time"].values
    return (str(np.datetime_as_string(t[0], unit="s")) + "Z",
            str(np.datetime_as_string(t[-1], unit="s")) + "Z")


def load_notes(ds: Any) -> list[str]:
    """Statements about the load: estimated, missing, converted, masked, ensemble."""
    notes: list[str] = []
    present = set(cv.present_variables(ds))
    if ds.attrs.get("waves_estimated"):
        notes.append(str(ds.attrs["waves_estimated"]))
    for group, names in _GROUPS.items():
        if not present.intersection(names):
            notes.append(f"no {group} in the forecast: {group} taken as zero")
    for n, rec in field_record(ds).items():
        if rec["masked_outliers"]:
            notes.append(f"{rec['masked_outliers']} impossible values of {n} in "
                         f"{rec['source_file']} masked as missing")
    held: dict[str, list[str]] = {}
    conv: set[str] = set()
    for n, rec in field_record(ds).items():
        for c in rec["conversion"].split("; "):
            if c.startswith(("held", "missing at")):
                held.setdefault(c, []).append(n)
            elif c and "estimated" not in c and "regridded" not in c:
                conv.add(c)
    notes.extend(f"{', '.join(names)} from {field_record(ds)[names[0]]['source_file']}: {c}"
                 for c, names in held.items())
    notes.extend(f"converted: {c}" for c in sorted(conv))
    if ds.attrs.get("grid_notes"):
        notes.append(f"grid: {ds.attrs['grid_notes']}")
    if ds.attrs.get("ensemble"):
        notes.append(f"ensemble: {ds.attrs['ensemble']}")
    return notes


def sources_by_field(ds: Any) -> dict[str, str]:
    """Canonical field -> the file it came from."""
    return {n: rec["source_file"] for n, rec in field_record(ds).items()}


def cycle_record(ds: Any) -> dict[str, Any]:
    """The record a sampler carries into planning: cycle, files, fields, range, notes."""
    first, last = valid_range(ds)
    files = [f.strip() for f in str(ds.attrs.get("source_files", "")).split(",") if f.strip()]
    return {"cycle_id": str(ds.attrs.get("cycle_id", "")), "source_files": files,
            "fields": field_record(ds), "valid_from": first, "valid_to": last,
            "notes": load_notes(ds)}


#: attributes that record provenance; they travel on the cycle announcement (field sources,
#: notes), not with each slice
VARIABLE_RECORD_ATTRS = ("source_file", "source_variable", "conversion", "masked_outliers")
DATASET_RECORD_ATTRS = ("source_files", "waves_estimated", "ensemble", "grid_notes")


def without_record(ds: Any) -> Any:
    """Copy of a canonical dataset without its provenance attributes (what slices carry)."""
    out = ds.copy()
    for n in out.data_vars:
        for k in VARIABLE_RECORD_ATTRS:
            out[n].attrs.pop(k, None)
    for k in DATASET_RECORD_ATTRS:
        out.attrs.pop(k, None)
    return out
