"""Dijkstra and A* on the lat/lon grid at constant RPM: path-only weather routing.

Time-dependent label setting: a node's label is the least fuel found to reach it, with the
arrival time it implies; settled nodes sail all their moves from that time. Nodes are settled
in buckets (delta-stepping): every open node whose key is within `delta_t` of the smallest is
settled at once and all their moves are sailed in one vectorised call. With `delta_t` below
the cheapest move's fuel no node of a bucket can improve another, so Dijkstra stays exact.
A* adds the calm-water fuel for the remaining great-circle distance at the same RPM as its
heuristic (the usual distance-based guide of grid routers; with following seas it can
overestimate, which is why A* may return a slightly worse path than Dijkstra, as in the
reference study). Legs breaking a seakeeping or engine limit carry a large fuel penalty
instead of being removed, so a path exists whenever the grid connects the ports.
"""

from __future__ import annotations

import heapq
from dataclasses import dataclass

import numpy as np
from shiproute_core.geodesy import inverse

from .errors import NoRouteFoundError
from .latlon_grid import LatLonGrid
from .legs import LegSailor

UNSAFE_LEG_PENALTY_T = 1000.0
BUCKET_SHARE_OF_CHEAPEST_MOVE = 0.5
ASTAR_BUCKET_SHARE = 0.2


@dataclass(frozen=True)
class GridPath:
    """A path found on the grid: node positions, arrival times and fuel at each node."""

    lon_deg: np.ndarray
    lat_deg: np.ndarray
    time_s: np.ndarray
    fuel_t: np.ndarray
    rpm: float
    settled_nodes: int
    leg_evaluations: int


def distance_to_end_m(grid: LatLonGrid) -> np.ndarray:
    """Geodesic distance from every node to the arrival node."""
    n = grid.n_nodes
    _, d = inverse(grid.lon_deg, grid.lat_deg, np.full(n, grid.lon_deg[grid.end]),
                   np.full(n, grid.lat_deg[grid.end]))
    return d


def calm_fuel_per_m(sailor: LegSailor, rpm: float) -> float:
    """Calm-water fuel per metre sailed at `rpm` [t/m]."""
    r = np.array([rpm])
    return float(sailor.calm_fuel_t_per_h(r)[0]) / 3600.0 / float(sailor.calm_speed_m_s(r)[0])


def bucket_width_t(grid: LatLonGrid, sailor: LegSailor, rpm: float) -> float:
    """Half the calm-water fuel of the shortest grid move (the delta-stepping bucket)."""
    return BUCKET_SHARE_OF_CHEAPEST_MOVE * grid.lat_step_deg * 111_000.0 * calm_fuel_per_m(
        sailor, rpm) * min(1.0, grid.lon_step_deg / grid.lat_step_deg)


def search_grid(
    grid: LatLonGrid,
    sailor: LegSailor,
    depart_s: float,
    rpm: float,
    astar: bool,
    delta_t: float | None = None,
) -> GridPath:
    """Least-fuel path from `grid.start` to `grid.end` at constant `rpm` (Dijkstra or A*)."""
    n = grid.n_nodes
    fuel = np.full(n, np.inf)
    time = np.full(n, np.inf)
    parent = np.full(n, -1, dtype=np.int64)
    closed = np.zeros(n, dtype=bool)
    h = distance_to_end_m(grid) * calm_fuel_per_m(sailor, rpm) if astar else np.zeros(n)
    if delta_t is None:  # buckets keep Dijkstra exact; A* keys are not, so small buckets
        delta_t = bucket_width_t(grid, sailor, rpm) * (ASTAR_BUCKET_SHARE if astar else 1.0)
    delta = delta_t
    fuel[grid.start], time[grid.start] = 0.0, depart_s
    heap: list[tuple[float, int]] = [(h[grid.start], grid.start)]
    settled = evals = 0
    while heap and not closed[grid.end]:
        bucket: list[int] = []
        limit = None
        while heap and (limit is None or heap[0][0] < limit):
            key, node = heapq.heappop(heap)
            if closed[node] or key > fuel[node] + h[node] + 1e-12:
                continue  # settled already or a stale entry
            closed[node] = True
            bucket.append(node)
            if limit is None:
                limit = key + delta
                if delta <= 0.0:
                    break
        if not bucket:
            break
        settled += len(bucket)
        src = np.asarray(bucket, dtype=np.int64)
        nb = grid.neighbours[src]
        rows, cols = np.nonzero(nb >= 0)
        s, d = src[rows], nb[rows, cols]
        live = ~closed[d]
        s, d = s[live], d[live]
        if s.size == 0:
            continue
        legs = sailor.between(grid.lon_deg[s], grid.lat_deg[s], grid.lon_deg[d], grid.lat_deg[d],
                              time[s], np.full(s.size, rpm))
        evals += s.size
        cost = fuel[s] + legs.fuel_t + np.where(legs.ok, 0.0, UNSAFE_LEG_PENALTY_T)
        order = np.lexsort((cost, d))
        first = np.r_[True, d[order][1:] != d[order][:-1]]
        best = order[first]
        better = best[cost[best] < fuel[d[best]]]
        tgt = d[better]
        fuel[tgt] = cost[better]
        time[tgt] = time[s[better]] + legs.duration_s[better]
        parent[tgt] = s[better]
        for j in tgt:
            heapq.heappush(heap, (fuel[j] + h[j], int(j)))
    if not closed[grid.end]:
        raise NoRouteFoundError(
            "the grid search did not reach the arrival port: land or the grid margin cuts it off"
        )
    path = [grid.end]
    while path[-1] != grid.start:
        path.append(int(parent[path[-1]]))
    idx = np.array(path[::-1])
    return GridPath(grid.lon_deg[idx], grid.lat_deg[idx], time[idx], fuel[idx], rpm, settled,
                    evals)


def shortest_sea_path(grid: LatLonGrid) -> tuple[np.ndarray, np.ndarray]:
    """Geometrically shortest port-to-port path on the grid (no weather), lon/lat of its nodes.

    Used as a land-free reference line where the great circle crosses land."""
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import dijkstra

    src, col = np.nonzero(grid.neighbours >= 0)
    dst = grid.neighbours[src, col]
    _, w = inverse(grid.lon_deg[src], grid.lat_deg[src], grid.lon_deg[dst], grid.lat_deg[dst])
    graph = csr_matrix((np.maximum(w, 1e-3), (src, dst)), shape=(grid.n_nodes, grid.n_nodes))
    dist, pred = dijkstra(graph, indices=grid.start, return_predecessors=True)
    if not np.isfinite(dist[grid.end]):
        raise NoRouteFoundError("no sea path between the ports on the search grid")
    path = [grid.end]
    while path[-1] != grid.start:
        path.append(int(pred[path[-1]]))
    idx = np.array(path[::-1])
    return grid.lon_deg[idx], grid.lat_deg[idx]
