"""Post-processing of graph paths: drop waypoints whose turn breaks the heading-change limit.

Grid and isochrone paths can contain turns sharper than the planner's per-stage heading-change
limit (mostly at port links). A waypoint with too sharp a turn is removed when the straight
leg joining its neighbours stays off land ("string pulling"); this only shortens the path.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from shiproute_core.geodesy import inverse

TURN_MARGIN_DEG = 5.0  # steered headings differ from courses by the current drift


def turn_angles_deg(lon_deg: np.ndarray, lat_deg: np.ndarray) -> np.ndarray:
    """Absolute course change at every interior waypoint."""
    az, _ = inverse(lon_deg[:-1], lat_deg[:-1], lon_deg[1:], lat_deg[1:])
    return np.abs((np.diff(az) + 180.0) % 360.0 - 180.0)


def limit_turns(
    lon_deg: np.ndarray,
    lat_deg: np.ndarray,
    max_turn_deg: float,
    crosses_land: Callable[[np.ndarray, np.ndarray, np.ndarray, np.ndarray], np.ndarray],
    max_rounds: int = 50,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(lon, lat, indices kept) of the path with sharp-turn waypoints removed where the
    shortcut stays at sea."""
    lon, lat = np.asarray(lon_deg, float), np.asarray(lat_deg, float)
    idx = np.arange(lon.size)
    limit = max_turn_deg - TURN_MARGIN_DEG
    for _ in range(max_rounds):
        if lon.size < 3:
            break
        turns = turn_angles_deg(lon, lat)
        sharp = np.flatnonzero(turns > limit) + 1  # waypoint indices
        if sharp.size == 0:
            break
        ok = ~np.asarray(crosses_land(lon[sharp - 1], lat[sharp - 1], lon[sharp + 1],
                                      lat[sharp + 1]), dtype=bool)
        if not ok.any():
            break
        # remove the sharpest removable waypoint; neighbours' turns change, so one per round
        k = int(sharp[ok][np.argmax(turns[sharp[ok] - 1])])
        lon, lat, idx = np.delete(lon, k), np.delete(lat, k), np.delete(idx, k)
    return lon, lat, idx
