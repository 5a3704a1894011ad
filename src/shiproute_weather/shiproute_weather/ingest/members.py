"""Several deterministic forecasts (e.g. GFS and ECMWF) as the members of one multi-model cycle.

Each member is loaded like a cycle of its own (`loaders.open_forecast`: its files combined,
waves estimated from wind where it has none), then put on the grid and valid times of the
first member with the `combine` machinery (trilinear, directions as vectors, persistence for a
bounded time beyond a member's own span) and stacked along `member` (`contract.members`).
Every member keeps its provenance: the variables' `source_file` / `conversion` name each
member's, the dataset's `member_sources` lists them.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from pathlib import Path

import xarray as xr

from ..contract import canonical as cv
from ..contract.members import MEMBER_DIM, check_unique_labels, stack_members
from ..contract.validate import validate
from ..errors import ForecastFileError, GridError
from .combine import check_overlap, onto
from .loaders import open_forecast


def member_label_of(ds: xr.Dataset, paths: Sequence[str | Path]) -> str:
    """A member's default label: its source ('gfs', 'ecmwf', ...) or the first file's stem."""
    source = str(ds.attrs.get("source", ""))
    text = source if source and source != "unknown" else Path(str(paths[0])).stem
    return re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-")[:40] or "member"


def open_members(members: Sequence[Sequence[str | Path]], labels: Sequence[str] = (),
                 required: Sequence[str] = (), cycle_id: str | None = None,
                 waves_from_wind: bool = True) -> xr.Dataset:
    """One multi-model cycle from deterministic forecasts: `members[k]` are the files of
    member k (one cycle each). Members are regridded onto the first member's grid and valid
    times; a member whose grid or times do not meet it is refused (GridError naming it).
    `labels` default to each member's source (made unique with its position when shared)."""
    if len(members) < 1 or any(len(files) == 0 for files in members):
        raise ForecastFileError("(members)", "every member needs at least one forecast file")
    loaded = []
    for files in members:
        ds = open_forecast(list(files), required=required, waves_from_wind=waves_from_wind)
        if MEMBER_DIM in ds.dims:
            where = ", ".join(str(f) for f in files)
            raise GridError(where, f"holds {ds.sizes[MEMBER_DIM]} ensemble members itself; "
                                   "give an ensemble file on its own, not as one member")
        loaded.append(ds)
    if labels:
        if len(labels) != len(members):
            raise GridError("(members)", f"{len(labels)} member labels for {len(members)} "
                                         "members")
        names = [str(x) for x in labels]
    else:
        names = [member_label_of(ds, files) for ds, files in zip(loaded, members, strict=True)]
        if len(set(names)) != len(names):
            names = [f"{n}-{k}" for k, n in enumerate(names)]
    check_unique_labels(names, "member labels")
    base = loaded[0]
    variables = cv.present_variables(base)
    on_grid = [base]
    for k, ds in enumerate(loaded[1:], start=1):
        missing = [n for n in variables if n not in ds.data_vars]
        if missing:
            raise GridError(str(ds.attrs.get("source_files", names[k])),
                            f"member {names[k]!r} lacks {missing} that member {names[0]!r} has; "
                            "members must hold the same fields")
        check_overlap(base, ds)
        moved = onto(ds, variables, base)
        moved.attrs = dict(ds.attrs)
        on_grid.append(moved)
    out = stack_members(on_grid, names, kind="multi-model")
    out.attrs["ensemble"] = (f"{len(names)} multi-model members ({', '.join(names)}) on the "
                             f"grid and valid times of {names[0]!r}")
    if cycle_id:
        out.attrs["cycle_id"] = cycle_id
    where = "; ".join(", ".join(str(f) for f in files) for files in members)
    return validate(out, where, required)


def member_file_groups(entries: Sequence[str]) -> list[list[str]]:
    """Member file lists from parameter entries 'a.grib2' or 'wind.grib2+waves.nc' (blank
    entries skipped)."""
    return [[f.strip() for f in e.split("+") if f.strip()] for e in entries if str(e).strip()]
