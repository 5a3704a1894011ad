"""Coastal passages computed on a fine navigable-water grid, not copied from the sea lane.

A passage runs from a port (berth or pilot station) to the sea end of its approach. The sea
lane between them is only a guide: a corridor of `corridor_nm` round it bounds a local
`geo.nav_grid` (cells of `cell_nm`, land at the best GSHHG resolution installed, clearance,
depth), and the shortest path through navigable cells is found by Dijkstra on the grid
(16 neighbours, so legs may run at 26.6-degree steps; diagonal moves may not cut a land
corner). Water nearer land than `prefer_off_nm` costs a little more, so a passage keeps
mid-channel where there is room; with a depth limit, water of unknown depth beyond pilotage
waters costs double, so a passage keeps to water known deep enough where there is some.
The path is straightened (a vertex is dropped while the straight line between its
neighbours stays in navigable cells, not cutting back into unknown depth) and checked
against the land polygons every 0.4 cells. Where nothing fits at `cell_nm` (a river,
sound or fjord narrower than a few cells), or only with less than the full clearance (a
strait's narrows lose a cell of width to each rasterised shore), the grid is refined to
`fine_cell_nm` before the corridor is widened, and the finer passage is kept when it leaves
more clearance. Where nothing at all fits at `fine_cell_nm` (an inner harbour whose basins
join the sea through channels of a few hundred metres: Sydney's), `finest_cell_nm` is tried
on grids of at most `FINEST_MAX_CELLS` before the corridor is widened.

Clearance: the passage keeps `clearances_nm[0]` (0.5 NM) from land where it can; a strait or
channel too narrow for it (Bosphorus, Dardanelles, an estuary) gets the largest clearance of
`clearances_nm` that leaves a way through, and the plan says so. With a clearance per point
(`need_nm`: a seed's search rule) each clearance tried caps that need cell by cell, so one
narrow part does not lower what the rest of the passage keeps. Within `berth_nm` of the
port only land blocks (harbour basins are narrower than any clearance); within
`pilotage_nm` depth is the pilot's (dredged channels are finer than the grids), beyond it
a cell shallower than the ship's required depth blocks, where a grid may decide (see
`geo.nav_grid` for coarse grids near the coast). With no deep-enough way through at any
clearance the corridor is widened first (the deep-water route of a coast with shoals runs
farther off than the lane: west of the North Frisian Islands), then the depth limit is
dropped (stated), and only when no corridor has any way through is the lane's own geometry
kept (stated).
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from scipy import ndimage
from shiproute_core.geodesy import M_PER_NM, inverse

from ..geo.gshhg import finest_resolution as best_land_resolution
from ..geo.nav_grid import NavGrid, build_nav_grid, grid_box, land_in_box, on_land
from .berths import BERTH_RADIUS_M
from .grid_path_lines import sight, straighten

# (d_row, d_col) of the 8 "forward" moves of a 16-neighbour stencil and the cells they cross
_MOVES = ((0, 1), (1, 0), (1, 1), (1, -1), (1, 2), (2, 1), (1, -2), (2, -1))
_CROSSED = {(0, 1): (), (1, 0): (), (1, 1): ((0, 1), (1, 0)), (1, -1): ((0, -1), (1, 0)),
            (1, 2): ((0, 1), (1, 1)), (2, 1): ((1, 0), (1, 1)),
            (1, -2): ((0, -1), (1, -1)), (2, -1): ((1, 0), (1, -1))}


#: extra cost per metre of water whose depth no grid decides (a coarse grid's coastal cells),
#: for a ship with a depth limit: a passage keeps to water known deep enough where it can
#: (the smeared band between a coast and its offshore banks is often shallower still)
UNKNOWN_DEPTH_COST = 1.0
#: the largest grid [cells] `finest_cell_nm` is tried on (~1-2 s to solve; a long strait's
#: corridor at 0.05 NM would take far longer)
FINEST_MAX_CELLS = 1_500_000


@dataclass(frozen=True)
class PassageRules:
    """How passages are computed (distances in NM, depth in m)."""

    clearances_nm: tuple[float, ...] = (0.5, 0.25, 0.1, 0.0)
    cell_nm: float = 0.25
    fine_cell_nm: float = 0.1  # tried when nothing fits at `cell_nm` (rivers, sounds, fjords)
    finest_cell_nm: float = 0.05  # tried when nothing fits at `fine_cell_nm` (inner harbours)
    corridors_nm: tuple[float, ...] = (10.0, 30.0)
    # tried only when no corridor above has any way through (0: never): a port approach
    # (`coastal_passages.passage_rules`) whose nearest sea-lane node lies behind a peninsula
    # (Lae: the lane's first hop crosses 50 NM of the Huon Peninsula) is left round it; a
    # shallow-water detour this far off is not sought, nor by repairs and straits
    widest_corridor_nm: float = 0.0
    # a port approach whose sea end no way reaches (a harbour basin behind breakwaters no
    # grid resolves: Peterhead's) ends in the water the port reaches within this of it
    # (0: never; repairs and straits must reach their ends)
    end_reach_nm: float = 0.0
    berth_nm: float = 3.0
    pilotage_nm: float = 10.0
    prefer_off_nm: float = 2.0
    required_depth_m: float | None = None
    bathymetry: object = field(default=None, compare=False)
    # clearance [NM] each point needs (lon, lat -> NM; a seed's search rule): with it each
    # of `clearances_nm` caps that need instead of being kept everywhere, so a detour keeps
    # the open-sea clearance in open water and less only where its water is narrower
    need_nm: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = field(
        default=None, compare=False, repr=False)


@dataclass(frozen=True, eq=False)
class Passage:
    """A computed passage (port first) and what it kept."""

    lon_deg: np.ndarray
    lat_deg: np.ndarray
    clearance_nm: float
    depth_limited: bool
    corridor_nm: float
    cell_nm: float = 0.25


def _dense_lane(lon: np.ndarray, lat: np.ndarray, step_deg: float) -> tuple[np.ndarray,
                                                                             np.ndarray]:
    """Lane points every ~`step_deg` (linear in lon/lat: lanes near a port are short)."""
    out_lon, out_lat = [lon[:1]], [lat[:1]]
    for k in range(lon.size - 1):
        n = max(int(np.ceil(np.hypot(lon[k + 1] - lon[k], lat[k + 1] - lat[k]) / step_deg)), 1)
        t = np.arange(1, n + 1) / n
        out_lon.append(lon[k] + t * (lon[k + 1] - lon[k]))
        out_lat.append(lat[k] + t * (lat[k + 1] - lat[k]))
    return np.concatenate(out_lon), np.concatenate(out_lat)


def _distance_from_m(grid: NavGrid, i: np.ndarray, j: np.ndarray) -> np.ndarray:
    """Distance [m] of every cell centre from the cells (i, j)."""
    from scipy import ndimage

    mask = np.ones(grid.shape, dtype=bool)
    mask[i, j] = False
    dy, dx = grid.cell_m
    return np.asarray(ndimage.distance_transform_edt(mask, sampling=(dy, dx)))


def _shortest_path(free: np.ndarray, cost: np.ndarray, cell_m: tuple[float, float],
                   pool: np.ndarray, port: tuple[int, int], goal: tuple[int, int]
                   ) -> np.ndarray | None:
    """Cells (rows of (i, j)) of the cheapest 16-neighbour path from the cell of `pool`
    nearest `port` that connects to the free cell `goal` (a harbour pond or a lake next to
    the berth does not count), in that order; None when no pool cell connects."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import dijkstra

    rows, cols = free.shape
    node = np.full(free.shape, -1, dtype=np.int64)
    fi, fj = np.nonzero(free)
    node[fi, fj] = np.arange(fi.size)
    src, dst, w = [], [], []
    dy, dx = cell_m
    for di, dj in _MOVES:
        ti, tj = fi + di, fj + dj
        ok = (ti >= 0) & (ti < rows) & (tj >= 0) & (tj < cols)
        a_i, a_j, b_i, b_j = fi[ok], fj[ok], ti[ok], tj[ok]
        ok = free[b_i, b_j]
        for ci, cj in _CROSSED[(di, dj)]:
            ci_i, cj_j = a_i + ci, a_j + cj
            inside = (ci_i >= 0) & (ci_i < rows) & (cj_j >= 0) & (cj_j < cols)
            ok &= inside & free[np.clip(ci_i, 0, rows - 1), np.clip(cj_j, 0, cols - 1)]
        a_i, a_j, b_i, b_j = a_i[ok], a_j[ok], b_i[ok], b_j[ok]
        length = float(np.hypot(di * dy, dj * dx))
        src.append(node[a_i, a_j])
        dst.append(node[b_i, b_j])
        w.append(length * 0.5 * (cost[a_i, a_j] + cost[b_i, b_j]))
    n = fi.size
    graph = coo_matrix((np.concatenate(w), (np.concatenate(src), np.concatenate(dst))),
                       shape=(n, n)).tocsr()
    g = int(node[goal])
    dist, pred = dijkstra(graph, directed=False, indices=g, return_predecessors=True)
    cand = np.flatnonzero(pool[fi, fj] & np.isfinite(dist))
    if cand.size == 0:
        return None
    path = [int(cand[np.argmin((fi[cand] - port[0]) ** 2 + (fj[cand] - port[1]) ** 2)])]
    while path[-1] != g:
        path.append(int(pred[path[-1]]))
    idx = np.array(path)
    return np.stack([fi[idx], fj[idx]], axis=1)


def _nearest_free(free: np.ndarray, i: int, j: int) -> tuple[int, int] | None:
    """The free cell nearest (i, j) (in cells), None if there is none."""
    fi, fj = np.nonzero(free)
    if fi.size == 0:
        return None
    k = int(np.argmin((fi - i) ** 2 + (fj - j) ** 2))
    return int(fi[k]), int(fj[k])


def _cell_need_m(grid: NavGrid, need_nm: Callable[[np.ndarray, np.ndarray], np.ndarray]
                 ) -> np.ndarray:
    """Clearance [m] each cell needs under a per-point rule: the largest need of its own and
    its eight neighbours' centres (a path through a cell runs up to a cell from its centre)."""
    from scipy import ndimage

    i, j = np.indices(grid.shape)
    lon, lat = grid.centre(i.ravel(), j.ravel())
    need = np.asarray(need_nm(lon, lat), dtype=float).reshape(grid.shape)
    return ndimage.maximum_filter(need, size=3, mode="nearest") * M_PER_NM


def solve_on_grid(grid: NavGrid, lane_lon: np.ndarray, lane_lat: np.ndarray,
                  rules: PassageRules, corridor_nm: float,
                  to_lane_end: bool = True) -> Passage | None:
    """Passage from the lane's first point (the port) to its last (the sea end) inside a
    corridor of `corridor_nm` round the lane, relaxing clearance then depth as needed.
    `to_lane_end=False`: to the centre of the free cell nearest to the sea end among those
    the port reaches (4-connected, as the path's diagonal moves need both sides free) within
    `rules.end_reach_nm` of it."""
    d_lon, d_lat = _dense_lane(lane_lon, lane_lat, 0.5 * min(grid.dlat_deg, grid.dlon_deg))
    li, lj = grid.cell_of(d_lon, d_lat)
    corridor = _distance_from_m(grid, li, lj) <= corridor_nm * M_PER_NM
    pi, pj = grid.cell_of(lane_lon[:1], lane_lat[:1])
    from_port = _distance_from_m(grid, pi, pj)
    berth = from_port <= rules.berth_nm * M_PER_NM
    water = ~grid.land & corridor
    shallow = np.zeros(grid.shape, dtype=bool)
    if rules.required_depth_m is not None:
        shallow = (grid.depth_m < rules.required_depth_m) & (
            from_port > rules.pilotage_nm * M_PER_NM)
    prefer_m = rules.prefer_off_nm * M_PER_NM
    cost = 1.0 + 0.5 * np.clip(1.0 - grid.clearance_m / prefer_m, 0.0, 1.0)
    unknown = np.zeros(grid.shape, dtype=bool)
    if rules.required_depth_m is not None and UNKNOWN_DEPTH_COST > 0:
        # known deep water before water of unknown depth
        unknown = np.isnan(grid.depth_m) & (from_port > rules.pilotage_nm * M_PER_NM)
        cost = cost + UNKNOWN_DEPTH_COST * unknown
    modes = ((False,) if rules.required_depth_m is None else
             (True, False) if shallow.any() else (True,))
    need_m = None if rules.need_nm is None else _cell_need_m(grid, rules.need_nm)
    gi, gj = grid.cell_of(lane_lon[-1:], lane_lat[-1:])
    near_end = (None if to_lane_end else
                _distance_from_m(grid, gi, gj) <= rules.end_reach_nm * M_PER_NM)
    for use_depth in modes:
        for c_nm in rules.clearances_nm:
            keep_m = (c_nm * M_PER_NM if need_m is None
                      else np.minimum(need_m, c_nm * M_PER_NM))
            free = water & (berth | (grid.clearance_m >= keep_m))
            if use_depth:
                free &= ~shallow
            pool = free & berth if (free & berth).any() else free
            targets = free & ~berth if (free & ~berth).any() else free
            if near_end is not None:  # not to the lane's end
                labels, _ = ndimage.label(free)
                reached = np.unique(labels[pool])
                targets &= np.isin(labels, reached[reached > 0]) & near_end
            goal = _nearest_free(targets, int(gi[0]), int(gj[0]))
            if goal is None:
                continue
            cells = _shortest_path(free, cost, grid.cell_m, pool, (int(pi[0]), int(pj[0])),
                                   goal)
            if cells is None:
                continue
            cells = straighten(sight(free, unknown, cells), cells,
                                20.0 / (60.0 * grid.dlat_deg))
            lon, lat = grid.centre(cells[:, 0], cells[:, 1])
            end = slice(-1, None) if to_lane_end else slice(0, 0)
            lon = np.concatenate([lane_lon[:1], lon, lane_lon[end]])
            lat = np.concatenate([lane_lat[:1], lat, lane_lat[end]])
            return Passage(lon, lat, c_nm, use_depth, corridor_nm,
                           float(grid.dlat_deg * 60.0))
    return None


_RES_NAMES = {"f": "full", "h": "high", "i": "intermediate"}


def best_land_name() -> str:
    """Words for the land data passages are computed with."""
    return f"GSHHG {_RES_NAMES[best_land_resolution()]} resolution"


@functools.lru_cache(maxsize=1)
def best_land_polygons():
    """Land polygons at the best GSHHG resolution installed, loaded once per process."""
    from ..geo.gshhg import load_land_polygons

    return load_land_polygons(best_land_resolution())


def passage_length_nm(lon: np.ndarray, lat: np.ndarray) -> float:
    """Geodesic length [NM] of a polyline."""
    return float(np.sum(inverse(lon[:-1], lat[:-1], lon[1:], lat[1:])[1])) / M_PER_NM


def compute_passage(lane_lon: np.ndarray, lane_lat: np.ndarray, rules: PassageRules,
                    polygons=None) -> Passage | None:
    """Passage from `lane[0]` (port) to `lane[-1]` (sea end), continuous longitudes; None
    when no corridor has a way through or the result fails the dense land check. With
    `end_reach_nm`, a sea end no way reaches (on land, or in a harbour basin behind
    breakwaters no grid resolves: Peterhead's) gives way to the free water nearest to it
    that the port reaches within that distance."""

    polygons = polygons if polygons is not None else best_land_polygons()
    lane_lon = np.asarray(lane_lon, dtype=float)
    lane_lat = np.asarray(lane_lat, dtype=float)
    shift = 360.0 * np.round(np.mean(lane_lon) / 360.0)
    lon_f = lane_lon - shift
    for to_lane_end in (True, False) if rules.end_reach_nm > 0 else (True,):
        p = _passage_on_grids(lon_f, lane_lat, rules, polygons, to_lane_end)
        if p is not None:
            return Passage(p.lon_deg + shift, p.lat_deg, p.clearance_nm, p.depth_limited,
                           p.corridor_nm, p.cell_nm)
    return None


def _passage_on_grids(lon_f: np.ndarray, lane_lat: np.ndarray, rules: PassageRules, polygons,
                      to_lane_end: bool) -> Passage | None:
    """`compute_passage` on its grids, coarsest and narrowest corridor first, in longitudes
    within -180..180; to the lane's sea end, or (`to_lane_end=False`) to the free water
    nearest to it that the port reaches."""
    tries = [(rules.corridors_nm[0], rules.cell_nm), (rules.corridors_nm[0], rules.fine_cell_nm),
             *([(rules.corridors_nm[0], rules.finest_cell_nm)]
               if rules.finest_cell_nm < rules.fine_cell_nm else []),
             *((w, rules.cell_nm) for w in rules.corridors_nm[1:]),
             *([(rules.widest_corridor_nm, rules.cell_nm)]
               if rules.widest_corridor_nm > max(rules.corridors_nm) else [])]
    found: Passage | None = None
    for corridor_nm, cell_nm in tries:
        if found is not None and _keeps_depth(found, rules) and (
                cell_nm >= found.cell_nm or corridor_nm > found.corridor_nm):
            return found
        if found is not None and corridor_nm > max(rules.corridors_nm):
            return found  # the widest corridor only where nothing has a way through
        finest = cell_nm < rules.fine_cell_nm
        if finest and found is not None:
            continue  # the finest grid only where nothing fits at all
        box = grid_box(lon_f, lane_lat, corridor_nm + 2.0, cell_nm)
        lon0, lat0, dlon, dlat, rows, cols = box
        if finest and rows * cols > FINEST_MAX_CELLS:
            continue
        if lon0 < -180.0 or lon0 + cols * dlon > 180.0:
            return None  # a box across the antimeridian: not supported, the lane is kept
        land = land_in_box(polygons, lon0, lat0, lon0 + cols * dlon, lat0 + rows * dlat)
        grid = build_nav_grid(land, box, rules.bathymetry)
        p = solve_on_grid(grid, lon_f, lane_lat, rules, corridor_nm, to_lane_end)
        if p is None or _crosses_land(p, land, rules):
            continue
        if not _better(p, found):
            if found is not None and _keeps_depth(found, rules):
                return found
            continue  # no deep-enough way yet: a wider corridor may hold one
        if _keeps_depth(p, rules) and (p.clearance_nm >= rules.clearances_nm[0]
                                       or cell_nm <= rules.fine_cell_nm):
            return p
        found = p  # narrow water: finer cells may leave a wider clearance; shallow water:
        # a wider corridor may hold the deep-water route
    return found


def _crosses_land(p: Passage, land: list, rules: PassageRules) -> bool:
    """True when the passage's dense samples (0.4 cells apart) touch land beyond the berth's:
    past `BERTH_RADIUS_M` along the track from the port, as the route check tests it (the
    berth zone keeps no clearance, but a leg from the berth to a basin the grid reaches only
    round a headland must not cut across it)."""
    from shiproute_core.geodesy import densify_track

    d_lon, d_lat = densify_track(p.lon_deg, p.lat_deg, 0.4 * p.cell_nm * M_PER_NM)
    d_lon, d_lat = np.asarray(d_lon, dtype=float), np.asarray(d_lat, dtype=float)
    _, step = inverse(d_lon[:-1], d_lat[:-1], d_lon[1:], d_lat[1:])
    along = np.concatenate([[0.0], np.cumsum(np.atleast_1d(np.asarray(step, dtype=float)))])
    out = along > min(rules.berth_nm * M_PER_NM, BERTH_RADIUS_M)
    return bool(np.any(on_land(land, d_lon[out], d_lat[out])))


def _keeps_depth(p: Passage, rules: PassageRules) -> bool:
    """True when `p` keeps the ship's depth limit, or there is none to keep."""
    return p.depth_limited or rules.required_depth_m is None


def _better(p: Passage, than: Passage | None) -> bool:
    """True when `p` keeps the depth limit where `than` does not, or keeps as much of it
    and more clearance from land."""
    if than is None:
        return True
    if p.depth_limited != than.depth_limited:
        return p.depth_limited
    return p.clearance_nm > than.clearance_nm
