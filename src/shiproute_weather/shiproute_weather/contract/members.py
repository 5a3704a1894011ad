"""Ensemble and multi-model members of a canonical dataset: count, labels, one member, mean, stack.

A canonical dataset MAY carry a leading dimension `member`: every data variable then has dims
(member, time, latitude, longitude); coordinate `member` is int64 0..M-1 with a string
coordinate `member_label` along it, and the dataset attr `member_kind` says "ensemble" (members
of one model run) or "multi-model" (several deterministic sources on one grid). A dataset
without the dimension is deterministic (one member).
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from ..errors import GridError
from . import canonical as cv

if TYPE_CHECKING:
    import xarray as xr

MEMBER_DIM = "member"
MEMBER_LABEL = "member_label"
MEMBER_KINDS = ("ensemble", "multi-model")
MEMBER_DIMS_ORDER = (MEMBER_DIM, "time", "latitude", "longitude")


def member_count(ds: xr.Dataset) -> int:
    """Members of a dataset (1 for a deterministic one)."""
    return int(ds.sizes.get(MEMBER_DIM, 1))


def member_labels(ds: xr.Dataset) -> tuple[str, ...]:
    """The members' labels ("0", "1", ... without a `member_label` coordinate; the source for
    a deterministic dataset)."""
    if MEMBER_DIM not in ds.dims:
        return (str(ds.attrs.get("source", "deterministic")),)
    if MEMBER_LABEL in ds.coords:
        return tuple(str(x) for x in ds[MEMBER_LABEL].values)
    return tuple(str(x) for x in range(ds.sizes[MEMBER_DIM]))


def select_member(ds: xr.Dataset, index: int) -> xr.Dataset:
    """Member `index` as a deterministic dataset (attr `member_label` names it)."""
    if MEMBER_DIM not in ds.dims:
        if index != 0:
            raise GridError(str(ds.attrs.get("cycle_id", "dataset")),
                            f"member {index} asked of a deterministic dataset (one member)")
        return ds
    n = ds.sizes[MEMBER_DIM]
    if not 0 <= index < n:
        raise GridError(str(ds.attrs.get("cycle_id", "dataset")),
                        f"member {index} outside 0..{n - 1}")
    label = member_labels(ds)[index]
    out = ds.isel({MEMBER_DIM: index}, drop=True)
    out = out.drop_vars([MEMBER_LABEL], errors="ignore")
    out.attrs = {k: v for k, v in ds.attrs.items() if k != "member_kind"}
    out.attrs["member_label"] = label
    return out


def ensemble_mean(ds: xr.Dataset) -> xr.Dataset:
    """Mean over members (directions as the mean of unit vectors; NaN members skipped), as a
    deterministic dataset; a deterministic dataset is returned unchanged."""
    if MEMBER_DIM not in ds.dims:
        return ds
    import xarray as xr

    data = {}
    for n in cv.present_variables(ds):
        v = ds[n].values
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)  # all-NaN nodes stay NaN
            if n in cv.DIRECTION_VARIABLES:
                rad = np.deg2rad(v.astype(np.float64))
                mean = np.rad2deg(np.arctan2(np.nanmean(np.sin(rad), axis=0),
                                             np.nanmean(np.cos(rad), axis=0))) % 360.0
            else:
                mean = np.nanmean(v, axis=0)
        data[n] = (("time", "latitude", "longitude"), mean.astype(np.float32),
                   dict(ds[n].attrs))
    attrs = {k: v for k, v in ds.attrs.items() if k != "member_kind"}
    attrs["ensemble"] = f"mean of {ds.sizes[MEMBER_DIM]} {ds.attrs.get('member_kind', '')} " \
                        "members".replace("  ", " ")
    out = xr.Dataset(data, coords={c: ds[c] for c in ("time", "latitude", "longitude")},
                     attrs=attrs)
    return cv.annotate(out)


def stack_members(members: Sequence[xr.Dataset], labels: Sequence[str] | None = None,
                  kind: str = "ensemble") -> xr.Dataset:
    """Deterministic datasets on one grid and times -> one dataset with a member dimension.

    Every member must have the same variables, grid and valid times (regrid them first:
    `ingest.members.open_members`); labels default to "0", "1", ... and must be unique.
    Per-member provenance is kept in `member_<attr>` variable attrs (lists per member).
    """
    import xarray as xr

    if not members:
        raise GridError("members", "no member datasets given")
    if kind not in MEMBER_KINDS:
        raise GridError("members", f"member_kind {kind!r}; expected one of {MEMBER_KINDS}")
    labels = [str(x) for x in (labels if labels is not None else range(len(members)))]
    if len(labels) != len(members):
        raise GridError("members", f"{len(labels)} labels for {len(members)} members")
    check_unique_labels(labels, "members")
    first = members[0]
    names = cv.present_variables(first)
    for k, m in enumerate(members[1:], start=1):
        where = f"member {labels[k]!r} ({m.attrs.get('source_files', m.attrs.get('source'))})"
        if MEMBER_DIM in m.dims:
            raise GridError(where, "already has a member dimension; stack deterministic ones")
        if cv.present_variables(m) != names:
            raise GridError(where, f"variables {cv.present_variables(m)} differ from {names} "
                                   f"of member {labels[0]!r}")
        for c in ("time", "latitude", "longitude"):
            a, b = first[c].values, m[c].values
            same = a.shape == b.shape and (np.array_equal(a, b) if c == "time"
                                           else np.allclose(a, b, atol=1e-9))
            if not same:
                raise GridError(where, f"its {c} axis differs from member {labels[0]!r}'s; "
                                       "members must share one grid and valid times")
    data = {}
    for n in names:
        arr = np.stack([np.asarray(m[n].transpose("time", "latitude", "longitude").values,
                                   dtype=np.float32) for m in members])
        attrs = dict(first[n].attrs)
        for key in ("source_file", "source_variable", "conversion"):
            per = [str(m[n].attrs.get(key, "")) for m in members]
            if len(set(per)) > 1:
                attrs[key] = " | ".join(f"{lab}: {p}" for lab, p in zip(labels, per, strict=True))
        data[n] = (MEMBER_DIMS_ORDER, arr, attrs)
    coords = {MEMBER_DIM: np.arange(len(members), dtype=np.int64),
              MEMBER_LABEL: (MEMBER_DIM, np.array(labels, dtype=object)),
              "time": first["time"].values, "latitude": first["latitude"].values,
              "longitude": first["longitude"].values}
    attrs = {k: v for k, v in first.attrs.items() if k != "member_label"}
    attrs["member_kind"] = kind
    files = [str(m.attrs.get("source_files", "")) for m in members]
    attrs["source_files"] = ", ".join(dict.fromkeys(f for f in files if f))
    if kind == "multi-model":
        attrs["source"] = "+".join(dict.fromkeys(str(m.attrs.get("source", "")) for m in members))
        attrs["member_sources"] = "; ".join(
            f"{lab}: {m.attrs.get('source', '')} from {m.attrs.get('source_files', '')}"
            for lab, m in zip(labels, members, strict=True))
    return cv.annotate(xr.Dataset(data, coords=coords, attrs=attrs))


def check_unique_labels(labels: Sequence[str], where: str) -> None:
    """Raise GridError naming the repeated labels when members share one."""
    from collections import Counter

    dup = sorted(x for x, k in Counter(labels).items() if k > 1)
    if dup:
        raise GridError(where, f"member labels {dup} appear more than once; each member needs "
                               "its own label")


def check_members(ds: xr.Dataset, where: str) -> None:
    """The member part of the contract: int64 0..M-1, unique labels, a known kind, every
    variable (member, time, latitude, longitude)."""
    if MEMBER_DIM not in ds.dims:
        return
    n = ds.sizes[MEMBER_DIM]
    if n < 1:
        raise GridError(where, "member dimension is empty")
    if MEMBER_DIM in ds.coords and not np.array_equal(
            np.asarray(ds[MEMBER_DIM].values), np.arange(n)):
        raise GridError(where, f"coordinate 'member' is {list(ds[MEMBER_DIM].values)[:10]}; "
                               f"expected 0..{n - 1}")
    check_unique_labels(member_labels(ds), where)
    kind = ds.attrs.get("member_kind")
    if kind not in MEMBER_KINDS:
        raise GridError(where, f"attribute 'member_kind' is {kind!r}; expected one of "
                               f"{', '.join(MEMBER_KINDS)}")
