"""Time-constrained A* with speed ext-nodes (Li et al. 2023) on the lat/lon grid.

Every grid node is split into one "ext-node" per RPM level: (node, level) means the ship reached
the node having sailed the last leg at that level. G is the (time, fuel) sailed so far; the
time heuristic is the great-circle distance left at the level's calm-water speed, the fuel
heuristic the distance left at the economic speed (the calm-water speed that covers the
great circle in the allowed time) times the calm fuel per metre there. Ext-nodes are expanded
in order of estimated total fuel, but only while their estimated total time is within the RTA;
an ext-node already in the open list is updated only when the new path is both faster and
cheaper (the paper's rule). The search ends when an ext-node of the arrival port is taken.
As in `grid_search`, ext-nodes within a small fuel bucket are expanded together in one
vectorised call.
"""

from __future__ import annotations

import heapq
from dataclasses import dataclass

import numpy as np

from .errors import NoRouteFoundError
from .grid_search import UNSAFE_LEG_PENALTY_T, bucket_width_t, distance_to_end_m
from .latlon_grid import LatLonGrid
from .legs import LegSailor


@dataclass(frozen=True)
class TcAstarResult:
    """The path found, its per-leg RPM, arrival times and the search effort."""

    lon_deg: np.ndarray
    lat_deg: np.ndarray
    rpm: np.ndarray
    time_s: np.ndarray
    fuel_t: float
    expansions: int
    leg_evaluations: int


def economic_rpm(sailor: LegSailor, rpm_levels: np.ndarray, speed_m_s: float) -> float:
    """RPM whose calm-water speed is `speed_m_s` (interpolated over the levels, clamped)."""
    speeds = sailor.calm_speed_m_s(rpm_levels)
    return float(np.interp(speed_m_s, speeds, rpm_levels))


def tc_astar_route(
    grid: LatLonGrid,
    sailor: LegSailor,
    depart_s: float,
    rta_s: float,
    rpm_levels: np.ndarray,
    max_expansions: int = 200_000,
) -> TcAstarResult:
    """Least-fuel path and RPM per leg arriving by `rta_s` (heuristic search, not exact)."""
    levels = np.asarray(rpm_levels, float)
    r = levels.size
    n = grid.n_nodes
    d_end = distance_to_end_m(grid)
    v_level = sailor.calm_speed_m_s(levels)
    v_eco = d_end[grid.start] / max(rta_s - depart_s, 1.0)
    rpm_eco = np.array([economic_rpm(sailor, levels, v_eco)])
    fuel_per_m = float(sailor.calm_fuel_t_per_h(rpm_eco)[0]) / 3600.0 / float(
        sailor.calm_speed_m_s(rpm_eco)[0])
    hf = d_end * fuel_per_m
    gt = np.full(n * r, np.inf)
    gf = np.full(n * r, np.inf)
    parent = np.full(n * r, -1, dtype=np.int64)
    closed = np.zeros(n * r, dtype=bool)
    heap: list[tuple[float, int]] = []
    for w in range(r):  # the start node's ext-nodes: leave at any level
        e = grid.start * r + w
        gt[e], gf[e] = depart_s, 0.0
        heapq.heappush(heap, (hf[grid.start], e))
    delta = bucket_width_t(grid, sailor, float(levels[0]))
    expansions = evals = 0
    goal = -1
    while heap and expansions < max_expansions and goal < 0:
        bucket: list[int] = []
        limit = None
        while heap and (limit is None or heap[0][0] < limit):
            key, e = heapq.heappop(heap)
            if closed[e] or key > gf[e] + hf[e // r] + 1e-9:
                continue  # stale heap entry
            node, w = divmod(e, r)
            if gt[e] + d_end[node] / v_level[w] > rta_s:
                continue  # cannot make the RTA at this level; revived only by a better update
            if limit is None:
                limit = key + delta
            closed[e] = True
            bucket.append(e)
            if node == grid.end:
                goal = e
                break
        if goal >= 0 or not bucket:
            break
        expansions += len(bucket)
        src = np.asarray(bucket, dtype=np.int64)
        nb = grid.neighbours[src // r]
        rows, cols = np.nonzero(nb >= 0)
        s_ext = np.repeat(src[rows], r)
        tgt_node = np.repeat(nb[rows, cols], r)
        lvl = np.tile(np.arange(r), rows.size)
        s_node = s_ext // r
        legs = sailor.between(grid.lon_deg[s_node], grid.lat_deg[s_node], grid.lon_deg[tgt_node],
                              grid.lat_deg[tgt_node], gt[s_ext], levels[lvl])
        evals += s_ext.size
        t_new = gt[s_ext] + legs.duration_s
        f_new = gf[s_ext] + legs.fuel_t + np.where(legs.ok, 0.0, UNSAFE_LEG_PENALTY_T)
        ext = tgt_node * r + lvl
        order = np.lexsort((f_new, ext))
        first = order[np.r_[True, ext[order][1:] != ext[order][:-1]]]
        x = ext[first]
        fresh = ~closed[x] & (np.isinf(gt[x]) | ((t_new[first] < gt[x]) & (f_new[first] < gf[x])))
        x, pick = x[fresh], first[fresh]
        gt[x], gf[x], parent[x] = t_new[pick], f_new[pick], s_ext[pick]
        for xi in x:
            heapq.heappush(heap, (gf[xi] + hf[xi // r], int(xi)))
    if goal < 0:
        raise NoRouteFoundError(
            f"time-constrained A* found no path arriving by the RTA after {expansions} expansions"
        )
    chain = [goal]
    while parent[chain[-1]] >= 0:
        chain.append(int(parent[chain[-1]]))
    chain = chain[::-1]
    nodes = np.array([c // r for c in chain])
    lv = np.array([c % r for c in chain])
    return TcAstarResult(
        grid.lon_deg[nodes], grid.lat_deg[nodes], levels[lv[1:]], gt[np.array(chain)],
        float(gf[goal]), expansions, evals,
    )
