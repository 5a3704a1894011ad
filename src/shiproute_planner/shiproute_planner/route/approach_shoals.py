"""Where a port approach may end for a ship with a depth limit: past the lane's shoals.

The optimised span starts at the approach's sea end, and the optimiser exempts only the
first `PILOTAGE_DEPTH_M` (10 NM) of its first leg from the depth constraint. A lane that runs
on over water shallower than the ship needs beyond that (Darwin: ETOPO5 reads 5-13 m for
20 NM west of the 25-NM approach end, across Beagle Gulf) leaves the first leg only the
headings that get off the shoal within 10 NM, and the sea-lane seed none. The shoal is also
too near the port for a shoal passage of its own (`shoal_passages`: its gate would lie in
the pilotage waters), so it is the approach's: the approach runs on along the lane until no
lane water known to be too shallow begins within 10 NM of its end, and its coastal passage,
computed with the ship's depth limit, finds the deep water round the shoal where the grid
shows some (and says when it does not).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from shiproute_core.geodesy import wrap_lon
from shiproute_core.units import M_PER_NM

from .evaluation import PILOTAGE_DEPTH_M

#: how far past its minimum an approach may run on past shoals: a longer shoal is the
#: lane's, not the port's (the optimiser and the shoal passages deal with it)
MAX_WALK_M = 100.0 * M_PER_NM


@dataclass(frozen=True)
class ShoalLimit:
    """Lane water an approach must not end on or just before: `depth_m(lon, lat)` [m] as
    the passages trust it (NaN unknown) below `need_m`, within `ahead_m` of the end."""

    depth_m: Callable[[np.ndarray, np.ndarray], np.ndarray] = field(compare=False,
                                                                    repr=False)
    need_m: float
    ahead_m: float = PILOTAGE_DEPTH_M
    step_m: float = 0.5 * M_PER_NM
    max_walk_m: float = MAX_WALK_M


@dataclass(frozen=True)
class ShoalWalk:
    """Where an approach ends after the walk: lane distance [m] (None when the shoals go on
    beyond the walk's limit) and the shallowest lane water it passed (depth [m], lon, lat;
    None when it did not move)."""

    end_m: float | None
    shallowest: tuple[float, float, float] | None = None


def past_shoals(points_at: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
                lane_m: float, start_m: float, limit_m: float, shoals: ShoalLimit
                ) -> ShoalWalk:
    """The first lane distance >= `start_m` (and <= `limit_m`) from which no lane water
    known to be shallower than `shoals.need_m` begins within `shoals.ahead_m`;
    `points_at(d)` gives the lane's points at distances `d` [m] along a lane `lane_m`
    long."""
    limit_m = min(limit_m, start_m + shoals.max_walk_m)
    d = np.arange(start_m, min(limit_m + shoals.ahead_m, lane_m) + 0.5 * shoals.step_m,
                  shoals.step_m)
    if d.size == 0:
        return ShoalWalk(start_m)
    lon, lat = points_at(d)
    depth = np.asarray(shoals.depth_m(lon, lat), dtype=float)
    shallow = depth < shoals.need_m  # NaN (unknown) is not
    n_ahead = round(shoals.ahead_m / shoals.step_m)
    k = 0
    while True:
        hits = np.flatnonzero(shallow[k:k + n_ahead + 1])
        if hits.size == 0:
            break
        k += int(hits[-1]) + 1
        if k >= d.size or d[k] > limit_m:
            return ShoalWalk(None)
    if k == 0:
        return ShoalWalk(start_m)
    j = int(np.nanargmin(np.where(shallow[:k], depth[:k], np.nan)))
    return ShoalWalk(float(d[k]), (float(depth[j]), float(lon[j]), float(lat[j])))


def end_past_shoals(points_at: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
                    lane_m: float, start_m: float, limit_m: float, shoals: ShoalLimit,
                    where: str) -> tuple[float, tuple[str, ...]]:
    """An approach's minimum length [m] along its lane (port first) moved on past the shoals
    next to its end (`past_shoals`), and what the plan says about it (nothing when no shoal
    is there)."""
    walk = past_shoals(points_at, lane_m, start_m, limit_m, shoals)
    if walk.end_m is None:
        return start_m, (
            f"coastal passage ({where}): the sea lane runs over water shallower than the "
            f"ship's {shoals.need_m:.1f} m (per the depth grid) within "
            f"{shoals.ahead_m / M_PER_NM:g} NM of the approach's end and on for more than "
            f"{shoals.max_walk_m / M_PER_NM:g} NM; the approach ends "
            f"{start_m / M_PER_NM:.0f} NM from the port regardless and the optimiser's "
            "depth constraint decides beyond the first leg's pilotage waters",)
    if walk.shallowest is None:
        return start_m, ()
    depth, s_lon, s_lat = walk.shallowest
    return walk.end_m, (
        f"coastal passage ({where}): runs on to at least {walk.end_m / M_PER_NM:.0f} NM from "
        f"the port along the sea lane (not {start_m / M_PER_NM:.0f} NM), past lane water "
        f"shallower than the ship's {shoals.need_m:.1f} m ({depth:.0f} m at {s_lat:.2f}, "
        f"{float(wrap_lon(s_lon)):.2f} per the depth grid) that begins within "
        f"{shoals.ahead_m / M_PER_NM:g} NM of where it would end, so the optimised passage "
        "starts clear of it",)
