"""A lat/lon search grid around the great circle for Dijkstra, A* and time-constrained A*.

Cells are square in metres at the middle latitude (the longitude step is the latitude step
divided by cos(mid latitude)), so 8 or 16 neighbour moves are close to isotropic. Nodes on
land and moves that touch land are removed with the planner's land test; the two ports are
extra nodes linked to nearby sea nodes, so the ports themselves need not lie on the grid.
Longitudes are continuous (an arrival east of 180 is written past 180).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from shiproute_core.geodesy import great_circle_points, inverse, unwrap_near
from shiproute_core.units import M_PER_NM

from .errors import BaselineGridError
from .legs import LegSailor

MOVES_8 = ((0, 1), (1, 1), (1, 0), (1, -1), (0, -1), (-1, -1), (-1, 0), (-1, 1))
MOVES_16 = (*MOVES_8, (1, 2), (2, 1), (2, -1), (1, -2), (-1, -2), (-2, -1), (-2, 1), (-1, 2))


@dataclass(frozen=True)
class LatLonGrid:
    """Search graph: node positions and, per node, neighbour indices (-1 = none)."""

    lon_deg: np.ndarray  # (n_nodes,)
    lat_deg: np.ndarray  # (n_nodes,)
    neighbours: np.ndarray  # (n_nodes, k) int64
    start: int
    end: int
    lat_step_deg: float
    lon_step_deg: float

    @property
    def n_nodes(self) -> int:
        return int(self.lon_deg.size)


def build_grid(
    sailor: LegSailor,
    start_lon_deg: float,
    start_lat_deg: float,
    end_lon_deg: float,
    end_lat_deg: float,
    lat_step_deg: float = 0.5,
    margin_deg: float = 6.0,
    neighbours: int = 16,
    max_abs_lat_deg: float = 65.0,
    port_link_cells: int = 3,
) -> LatLonGrid:
    """Grid covering the great circle's bounding box plus `margin_deg`, land removed."""
    if neighbours not in (8, 16):
        raise BaselineGridError(f"neighbours={neighbours}: only 8 or 16 are supported")
    end_lon = float(unwrap_near(end_lon_deg, start_lon_deg))
    gc_lon, gc_lat = great_circle_points(start_lon_deg, start_lat_deg, end_lon, end_lat_deg, 200)
    lat_lo = max(gc_lat.min() - margin_deg, -max_abs_lat_deg)
    lat_hi = min(gc_lat.max() + margin_deg, max_abs_lat_deg)
    mid_lat = 0.5 * (lat_lo + lat_hi)
    lon_step = lat_step_deg / max(np.cos(np.radians(mid_lat)), 0.2)
    lon_margin = margin_deg / max(np.cos(np.radians(mid_lat)), 0.2)
    lats = np.arange(lat_lo, lat_hi + 1e-9, lat_step_deg)
    lons = np.arange(gc_lon.min() - lon_margin, gc_lon.max() + lon_margin + 1e-9, lon_step)
    n_lat, n_lon = lats.size, lons.size
    if n_lat < 2 or n_lon < 2:
        raise BaselineGridError(f"grid of {n_lat}x{n_lon} nodes is too small; lower lat_step_deg")
    glon, glat = np.meshgrid(lons, lats)
    sea = ~np.asarray(sailor.on_land(glon.ravel(), glat.ravel()), dtype=bool)
    index = np.full(n_lat * n_lon, -1, dtype=np.int64)
    index[sea] = np.arange(int(sea.sum()))
    moves = MOVES_8 if neighbours == 8 else MOVES_16
    k = len(moves)
    rows, cols = np.divmod(np.flatnonzero(sea), n_lon)
    nbr = np.full((rows.size, k + 1), -1, dtype=np.int64)  # last column: link to the end port
    for m, (di, dj) in enumerate(moves):
        r2, c2 = rows + di, cols + dj
        inside = (r2 >= 0) & (r2 < n_lat) & (c2 >= 0) & (c2 < n_lon)
        tgt = np.full(rows.size, -1, dtype=np.int64)
        tgt[inside] = index[r2[inside] * n_lon + c2[inside]]
        nbr[:, m] = tgt
    lon_n, lat_n = glon.ravel()[sea], glat.ravel()[sea]
    # drop moves that touch land (one batched test over every candidate edge)
    src, col = np.nonzero(nbr[:, :k] >= 0)
    dst = nbr[src, col]
    bad = np.asarray(sailor.crosses_land(lon_n[src], lat_n[src], lon_n[dst], lat_n[dst]), bool)
    nbr[src[bad], col[bad]] = -1
    # the two ports as extra nodes
    n_sea = lon_n.size
    start_id, end_id = n_sea, n_sea + 1
    lon_all = np.r_[lon_n, start_lon_deg, end_lon]
    lat_all = np.r_[lat_n, start_lat_deg, end_lat_deg]
    radius_m = port_link_cells * lat_step_deg * 111_120.0 * 1.5
    start_links = _port_links(sailor, lon_n, lat_n, start_lon_deg, start_lat_deg, radius_m, True)
    end_links = _port_links(sailor, lon_n, lat_n, end_lon, end_lat_deg, radius_m, False)
    if start_links.size == 0 or end_links.size == 0:
        which = "departure" if start_links.size == 0 else "arrival"
        raise BaselineGridError(
            f"no sea grid node within {radius_m / M_PER_NM:.0f} NM of the {which} port reachable "
            "without touching land; use a finer lat_step_deg or a larger port_link_cells"
        )
    width = max(k + 1, start_links.size)
    table = np.full((n_sea + 2, width), -1, dtype=np.int64)
    table[:n_sea, : k + 1] = nbr
    table[end_links, k] = end_id
    table[start_id, : start_links.size] = start_links
    return LatLonGrid(lon_all, lat_all, table, start_id, end_id, lat_step_deg, float(lon_step))


def _port_links(
    sailor: LegSailor,
    lon_n: np.ndarray,
    lat_n: np.ndarray,
    port_lon: float,
    port_lat: float,
    radius_m: float,
    outbound: bool,
) -> np.ndarray:
    """Sea nodes within `radius_m` of a port whose straight link to it stays off land."""
    _, dist = inverse(np.full(lon_n.size, port_lon), np.full(lat_n.size, port_lat), lon_n, lat_n)
    near = np.flatnonzero(dist <= radius_m)
    if near.size == 0:
        return near
    p_lon = np.full(near.size, port_lon)
    p_lat = np.full(near.size, port_lat)
    if outbound:
        bad = sailor.crosses_land(p_lon, p_lat, lon_n[near], lat_n[near])
    else:
        bad = sailor.crosses_land(lon_n[near], lat_n[near], p_lon, p_lat)
    return near[~np.asarray(bad, dtype=bool)]
