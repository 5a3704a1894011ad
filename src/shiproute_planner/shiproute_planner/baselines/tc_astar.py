"""Time-constrained A* with speed ext-nodes (Li et al. 2023) on the lat/lon grid.

Every grid node is split into one "ext-node" per RPM level: (node, level) means the ship reached
the node having sailed the last leg at that level. G is the (time, fuel) sailed so far; the
time heuristic is the great-circle distance left at the level's calm-water speed, the fuel
heuristic the distance left at the economic speed (the calm-water speed that covers the
great circle in the allowed time) times the calm fuel per metre there. Ext-nodes are expanded
in order of estimated total fuel, but only while their estimated total time is within the RTA;
an ext-node already in the open list is updated only when the new path is both faster and
cheaper (the paper's rule). The search ends when an ext-node of the arrival port is taken.
"""

from __future__ import annotations

import heapq
from dataclasses import dataclass

import numpy as np

from .errors import NoRouteFoundError
from .grid_search import UNSAFE_LEG_PENALTY_T, distance_to_end_m
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
    expansions = evals = 0
    goal = -1
    while heap and expansions < max_expansions:
        key, e = heapq.heappop(heap)
        if closed[e] or key > gf[e] + hf[e // r] + 1e-9:
            continue  # stale heap entry
        node, w = divmod(e, r)
        if gt[e] + d_end[node] / v_level[w] > rta_s:
            continue  # cannot make the RTA at this level; kept only if a later update improves it
        closed[e] = True
        expansions += 1
        if node == grid.end:
            goal = e
            break
        nb = grid.neighbours[node]
        nb = nb[nb >= 0]
        if nb.size == 0:
            continue
        nbr = np.repeat(nb, r)
        lvl = np.tile(np.arange(r), nb.size)
        m = nbr.size
        legs = sailor.between(np.full(m, grid.lon_deg[node]), np.full(m, grid.lat_deg[node]),
                              grid.lon_deg[nbr], grid.lat_deg[nbr], np.full(m, gt[e]), levels[lvl])
        evals += m
        t_new = gt[e] + legs.duration_s
        f_new = gf[e] + legs.fuel_t + np.where(legs.ok, 0.0, UNSAFE_LEG_PENALTY_T)
        ext = nbr * r + lvl
        fresh = ~closed[ext] & (
            np.isinf(gt[ext]) | ((t_new < gt[ext]) & (f_new < gf[ext]))
        )
        for x, tn, fn in zip(ext[fresh], t_new[fresh], f_new[fresh], strict=True):
            if tn < gt[x] or np.isinf(gt[x]):
                gt[x], gf[x], parent[x] = tn, fn, e
                heapq.heappush(heap, (fn + hf[x // r], int(x)))
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
