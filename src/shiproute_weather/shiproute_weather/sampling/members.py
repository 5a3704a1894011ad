"""Ensemble members in the sampler: every member packed into one stacked array, their weighted
mean as the sampler's deterministic view, and the members carried through time bounding.

A canonical dataset MAY lead with a `member` dimension (coordinate `member` 0..M-1, string
coordinate `member_label`, optional `member_weight`, attr `member_kind`). The planner's
compiled route kernels read the stacked (member, time, latitude, longitude, channel) array
(`member_kernel_data`); everything that samples one forecast sees the weighted member mean
of the packed channels (directions as the mean of their unit vectors).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["MemberFields", "bounded_members", "member_weights", "pack_members"]

MEMBER_DIM = "member"


@dataclass(frozen=True)
class MemberFields:
    """Stacked member fields (M, time, lat, lon, channel), their labels, weights (sum 1) and
    kind ("ensemble" | "multi-model")."""

    data: np.ndarray
    labels: tuple[str, ...]
    weights: np.ndarray
    kind: str

    @property
    def count(self) -> int:
        """Number of members."""
        return int(self.data.shape[0])

    @property
    def kernel_data(self) -> np.ndarray:
        """The stacked array as compiled kernels read it (half precision as uint16 bits)."""
        return self.data.view(np.uint16) if self.data.dtype == np.float16 else self.data


def member_weights(ds: xr.Dataset) -> np.ndarray:
    """Member weights summing to 1: the `member_weight` coordinate if present, else equal."""
    m = int(ds.sizes.get(MEMBER_DIM, 1))
    if "member_weight" in ds.coords:
        w = np.asarray(ds["member_weight"].values, dtype=np.float64).reshape(-1)
        if w.size != m or not np.all(np.isfinite(w)) or np.any(w < 0) or w.sum() <= 0:
            raise ValueError(f"member_weight must be {m} finite weights >= 0 with a positive "
                             f"sum, got {w.tolist()}")
        return w / w.sum()
    return np.full(m, 1.0 / m)


#: `sampler.pack_fields`: fill a packed array from the values of each named field
PackFn = Callable[[np.ndarray, Sequence[str], Callable[[str], np.ndarray]], None]


def pack_members(ds: xr.Dataset, names: Sequence[str], shape: tuple[int, ...],
                 dtype: np.dtype, member_dtype: np.dtype,
                 pack_fields: PackFn) -> tuple[np.ndarray, MemberFields]:
    """(weighted member mean packed in `dtype`, every member packed in `member_dtype`).

    `shape` is the (time, lat, lon, channel) shape of one member's packed array. A one-member
    dataset packs exactly as the same deterministic dataset would (no averaging)."""
    m = int(ds.sizes[MEMBER_DIM])
    weights = member_weights(ds)
    members = np.empty((m, *shape), dtype=member_dtype)
    mean = np.zeros(shape, dtype=np.float64)
    one = np.empty(shape, dtype=np.float32)
    def values_of(member: xr.Dataset) -> Callable[[str], np.ndarray]:
        return lambda n: member[n].transpose("time", "latitude", "longitude").values

    for k in range(m):
        pack_fields(one, names, values_of(ds.isel({MEMBER_DIM: k})))
        mean += weights[k] * one
        members[k] = one
    if m == 1:  # exactly the deterministic packing
        mean_out = np.empty(shape, dtype=dtype)
        pack_fields(mean_out, names, values_of(ds.isel({MEMBER_DIM: 0})))
    else:
        mean_out = mean.astype(dtype)
    labels = (tuple(str(v) for v in ds["member_label"].values) if "member_label" in ds.coords
              else tuple(f"member {k}" for k in range(m)))
    kind = str(ds.attrs.get("member_kind", "ensemble"))
    return mean_out, MemberFields(np.ascontiguousarray(members), labels, weights, kind)


def bounded_members(members: MemberFields, times_s: np.ndarray, bounded_times_s: np.ndarray,
                    bounded_data: np.ndarray, persistence_s: float) -> MemberFields:
    """Members extended to the valid times of a time-bounded sampler (`ingest.coverage.
    bounded_in_time`): each member holds its own edge fields where the bounded sampler
    persists the edge (`persistence_s` beyond it) and shares the added missing/climatology
    slices; the forecast's own times keep every member's fields."""
    t = np.asarray(times_s)
    bt = np.asarray(bounded_times_s)
    head = int(np.searchsorted(bt, t[0]))
    n_t = t.size
    out = np.empty((members.count, bt.size, *members.data.shape[2:]), dtype=members.data.dtype)
    for j, tj in enumerate(bt):
        if head <= j < head + n_t:
            out[:, j] = members.data[:, j - head]
        elif persistence_s > 0 and tj == t[0] - persistence_s:
            out[:, j] = members.data[:, 0]
        elif persistence_s > 0 and tj == t[-1] + persistence_s:
            out[:, j] = members.data[:, -1]
        else:
            out[:, j] = bounded_data[j].astype(members.data.dtype)
    return MemberFields(out, members.labels, members.weights, members.kind)
