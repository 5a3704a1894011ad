"""An ensemble cycle on the chart: members are members, not extra forecast times.

A cycle of M members and T valid times arrives as M x T slices (slice index = member x T +
time). For the page this module gives the valid times (one axis for every member), the slice
of one member at a time index, a combined view per valid time (each cell's P90 of the members'
thinned Hs, i.e. the height only one member in ten exceeds there, and the members' mean wind),
and each member's Hs-peak track (where that member's highest Hs lies at each valid time: the
storm's sea as that member places it).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from .forecast_view import HS_MISSING, SliceView

#: quantile of the members' Hs shown as the combined view
SPREAD_QUANTILE = 0.9


def member_slice_index(member: int, time_index: int, times_per_member: int) -> int:
    """Slice index of `member` at valid time `time_index` (ForecastSlice.msg ordering)."""
    return member * times_per_member + time_index


def valid_times(views: Mapping[int, SliceView], members: int, slice_count: int
                ) -> tuple[list[int], list[float]]:
    """(time indices, valid times) received so far of a cycle, in order, from any member's
    slices (a partial cycle may lack some)."""
    per = max(1, slice_count // max(1, members))
    times: dict[int, float] = {}
    for index, view in views.items():
        times.setdefault(index % per, view.valid_s)
    order = sorted(times)
    return order, [times[k] for k in order]


def hs_values(view: SliceView) -> np.ndarray:
    """Thinned Hs of a view in metres (NaN where no value), shape (n_lat, n_lon)."""
    codes = np.frombuffer(view.hs_codes, dtype=np.uint8)
    g = view.hs_grid
    hs = np.where(codes == HS_MISSING, np.nan, codes * 0.1)
    return hs.reshape(g.n_lat, g.n_lon)


def combined_view(members: list[SliceView], time_index: int) -> SliceView:
    """One valid time over all members: each cell's P90 of the members' Hs, the mean wind at
    the barb positions every member has (members share one grid, so the thinning is alike)."""
    first = members[0]
    stack = np.stack([hs_values(v) for v in members])
    with np.errstate(all="ignore"):
        finite = np.isfinite(stack).any(axis=0)
        q = np.nanquantile(np.where(finite[None], stack, 0.0), SPREAD_QUANTILE, axis=0)
    codes = np.where(finite, np.clip(np.round(q / 0.1), 0, HS_MISSING - 1), HS_MISSING)
    wind = list(first.wind)
    same = all(len(v.wind) == len(first.wind) for v in members)
    if same and wind:
        arr = np.array([v.wind for v in members], dtype=np.float64).reshape(len(members), -1, 4)
        mean = arr[0].copy()
        mean[:, 2:] = arr[:, :, 2:].mean(axis=0)
        wind = np.round(mean, 2).ravel().tolist()
    return SliceView(time_index, first.valid_s, first.hs_grid,
                     codes.astype(np.uint8).tobytes(), tuple(wind), member=-1)


def hs_peak_track(views: list[SliceView]) -> list[list[float]]:
    """[lon_deg, lat_deg, valid_s, hs_m] of the highest thinned Hs of each view, in order
    (views without any Hs are skipped)."""
    out: list[list[float]] = []
    for v in views:
        hs = hs_values(v)
        if not np.isfinite(hs).any():
            continue
        i, j = np.unravel_index(int(np.nanargmax(hs)), hs.shape)
        g = v.hs_grid
        out.append([round(g.lon0_deg + j * g.dlon_deg, 3), round(g.lat0_deg + i * g.dlat_deg, 3),
                    v.valid_s, round(float(hs[i, j]), 1)])
    return out
