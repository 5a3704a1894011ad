"""Dijkstra and A* on the lat/lon grid at constant RPM: path-only weather routing.

Time-dependent label setting: a node's label is the least fuel found to reach it, with the
arrival time it implies; when a node is settled, all its moves are sailed in one vectorised
call from that time. A* adds the calm-water fuel for the remaining great-circle distance at
the same RPM as its heuristic (the usual distance-based guide of grid routers; with following
seas it may overestimate, which is why the reference study's A* finds slightly worse paths
than Dijkstra). Legs breaking a seakeeping or engine limit carry a large fuel penalty instead
of being removed, so a path always exists if the grid connects the ports.
"""

from __future__ import annotations

import heapq
from dataclasses import dataclass

import numpy as np

from .errors import NoRouteFoundError
from .geodesy import inverse
from .latlon_grid import LatLonGrid
from .legs import LegSailor

UNSAFE_LEG_PENALTY_T = 1000.0


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


def search_grid(
    grid: LatLonGrid,
    sailor: LegSailor,
    depart_s: float,
    rpm: float,
    astar: bool,
) -> GridPath:
    """Least-fuel path from `grid.start` to `grid.end` at constant `rpm` (Dijkstra or A*)."""
    n = grid.n_nodes
    fuel = np.full(n, np.inf)
    time = np.full(n, np.inf)
    parent = np.full(n, -1, dtype=np.int64)
    closed = np.zeros(n, dtype=bool)
    if astar:
        per_m = float(sailor.calm_fuel_t_per_h(np.array([rpm]))[0]) / 3600.0
        per_m /= float(sailor.calm_speed_m_s(np.array([rpm]))[0])
        h = distance_to_end_m(grid) * per_m
    else:
        h = np.zeros(n)
    fuel[grid.start], time[grid.start] = 0.0, depart_s
    heap: list[tuple[float, int]] = [(h[grid.start], grid.start)]
    settled = evals = 0
    while heap:
        _, node = heapq.heappop(heap)
        if closed[node]:
            continue
        closed[node] = True
        settled += 1
        if node == grid.end:
            break
        nb = grid.neighbours[node]
        nb = nb[(nb >= 0)]
        nb = nb[~closed[nb]]
        if nb.size == 0:
            continue
        m = nb.size
        legs = sailor.between(
            np.full(m, grid.lon_deg[node]),
            np.full(m, grid.lat_deg[node]),
            grid.lon_deg[nb],
            grid.lat_deg[nb],
            np.full(m, time[node]),
            np.full(m, rpm),
        )
        evals += m
        cost = fuel[node] + legs.fuel_t + np.where(legs.ok, 0.0, UNSAFE_LEG_PENALTY_T)
        better = cost < fuel[nb]
        for j, c, dt in zip(nb[better], cost[better], legs.duration_s[better], strict=True):
            fuel[j], time[j], parent[j] = c, time[node] + dt, node
            heapq.heappush(heap, (c + h[j], int(j)))
    if not closed[grid.end]:
        raise NoRouteFoundError(
            "the grid search did not reach the arrival port: land or the grid margin cuts it off"
        )
    path = [grid.end]
    while path[-1] != grid.start:
        path.append(int(parent[path[-1]]))
    idx = np.array(path[::-1])
    return GridPath(
        grid.lon_deg[idx], grid.lat_deg[idx], time[idx], fuel[idx], rpm, settled, evals
    )
