"""The land test of every evaluated route: the clearance walk of one problem's legs.

One object per problem holds what `_land_walk.clearance_walk` reads (the finest coastline's
coarse clear distances and level 0, the shared level-1 tiles, the room raster, the problem's
clearance rule and span ends); `segments` walks legs on the planner's threads, builds the
tiles the walk met for the first time and walks those legs again, so a verdict never depends
on which tiles earlier plans built. Legs the walk marks as passing tight water (too narrow
for a straight stage leg to follow the full-resolution coast) are tested there on the
search's intermediate coastline (`_route_kernel.ga_land_hits`, exact in coastal cells); the
final repair threads them at full resolution: a leg's violations there count only as far as
that coastline confirms them (the smaller of the two counts), so a stage leg through a
strait the intermediate coastline leaves open and a full-resolution detour through it both
pass. Level 1 cannot tell a cell on land from one touching it, so a full-resolution detour
hugging a ~0.4-NM channel (Hayatomo Seto) reads as land to both; the exact evaluator
(`exact_tight`) settles tight-water land with the polygons instead, every 0.25 NM (the final
check's test), so such a detour is feasible in the final choice. The GA's evaluator, the exact
one, the seeds and the baselines call the same test; `search=False` measures the clearance
in tight water too (the check). Beyond the problem's latitude bound and ends (plus a margin) a
search walk reads level 0 alone and counts what it leaves undecided as too close: no route may sail
there, and the tiles there would cost time only.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from ..chunks import in_chunks
from ..geo.clear_distance import banded_clear_distance_deg
from ..geo.landmask import LandMask
from . import _fast_kernels as fk
from . import _land_walk as lw
from . import _route_kernel as rk
from .clearance import NARROWS_REACH_NM, ClearanceRule
from .problem import RouteProblem

COARSE_FACTOR = 10  # 0.05 deg raster -> 0.5 deg near-land filter
_COARSE: dict[int, tuple[np.ndarray, np.ndarray]] = {}
# beyond the latitude bound by more than this a search walk reads level 0 alone (a leg
# ending within the bound bulges past it by well under a degree)
LEVEL1_LAT_MARGIN_DEG = 1.0
MISS_BUFFER = 4096  # unbuilt level-1 tiles (or unresolved coastal cells) one walk may report
Work = Callable[[int, int], None]


class LandWalk:
    """The clearance walk of one problem (see the module docstring)."""

    def __init__(self, problem: RouteProblem, land: LandMask | None = None,
                 search: bool = True, exact_tight: bool = False) -> None:
        from ..geo.fine_distance import default_fine_distance
        from ..geo.full_land import final_land
        from ..geo.landmask import default_land_mask
        from ..geo.narrow_water import room_for
        finest = final_land().mask
        self.coarse, self.clear, self.coarse_deg = coarse_land(finest)
        self.coast_dist = np.asarray(finest.coast_distance)
        self.cell_deg = finest.cell_deg
        self.fine = default_fine_distance()
        rule = problem.limits.clearance
        self.room = np.asarray(room_for(rule.narrows, NARROWS_REACH_NM))
        self.spacing_deg = problem.land_spacing_deg
        # a search reads no level-1 tile beyond its latitude bound (or its ends, if farther):
        # a population's strays into the Arctic would build (and save) tiles no feasible
        # route needs, ~20 ms each
        bound = max(problem.limits.lat_bound_deg, abs(problem.dep_lat_deg),
                    abs(problem.arr_lat_deg))
        level1_lat = bound + LEVEL1_LAT_MARGIN_DEG if search else 90.0
        self.rule = problem.limits.clearance.kernel_array(search, level1_lat)
        self.ends = np.array([*lw.unit_vector(problem.dep_lat_deg, problem.dep_lon_deg),
                              *lw.unit_vector(problem.arr_lat_deg, problem.arr_lon_deg)])
        self.land = land if land is not None else default_land_mask()  # tight water's test
        self._land_arrays: tuple | None = None
        self.exact_tight = exact_tight

    def segments(self, lon0: np.ndarray, lat0: np.ndarray, lon1: np.ndarray,
                 lat1: np.ndarray, alongside: Work | None = None) -> np.ndarray:
        """Violations of great-circle segments (any shape; 0 = clear): samples on land or
        closer to the coast than the rule allows. `alongside(a, b)`: work on segments a..b
        run in the first pass's threads (one fan-out for both)."""
        shape = np.shape(lon0)
        ends = [np.ascontiguousarray(e, dtype=float).ravel() for e in (lon0, lat0, lon1, lat1)]
        out = np.empty(ends[0].size, dtype=np.int64)
        tight = np.zeros(ends[0].size, dtype=np.int64)
        todo = np.arange(out.size)
        first = True
        while todo.size:
            x0, y0, x1, y1 = ends if first else [e[todo] for e in ends]
            got = np.empty(todo.size, dtype=np.int64)
            marks = np.zeros(todo.size, dtype=np.int64)
            misses: list[np.ndarray] = []
            slots, grids = self.fine.slots, self.fine.grids  # one consistent pair per pass

            def walk(a: int, b: int, x0: np.ndarray = x0, y0: np.ndarray = y0,
                     x1: np.ndarray = x1, y1: np.ndarray = y1, got: np.ndarray = got,
                     marks: np.ndarray = marks, misses: list[np.ndarray] = misses,
                     extra: Work | None = alongside, slots: np.ndarray = slots,
                     grids: np.ndarray = grids) -> None:
                buf = np.empty(MISS_BUFFER, dtype=np.int64)
                n = lw.clearance_walk(x0[a:b], y0[a:b], x1[a:b], y1[a:b], self.coarse,
                                      self.clear, self.coarse_deg, self.coast_dist,
                                      self.cell_deg, self.spacing_deg, slots, grids, self.ends,
                                      self.rule, self.room, buf, got[a:b], marks[a:b])
                misses.append(buf[:n])
                if extra is not None:
                    extra(a, b)

            in_chunks(todo.size, walk)
            out[todo] = got
            tight[todo] = marks
            if any(m.size for m in misses):
                self.fine.add(np.concatenate(misses))
            todo = todo[got < 0]
            first, alongside = False, None
        near = np.flatnonzero(tight)
        if near.size:
            part = [e[near] for e in ends]
            confirmed = (self._exact_hits(*part) if self.exact_tight
                         else self._intermediate_hits(*part))
            out[near] += np.minimum(tight[near], confirmed)
        return out.reshape(shape)

    def _intermediate_hits(self, lon0: np.ndarray, lat0: np.ndarray, lon1: np.ndarray,
                           lat1: np.ndarray) -> np.ndarray:
        """Land samples of segments on the search's intermediate coastline (coastal cells
        resolved exactly as they are met; `_route_kernel.ga_land_hits`)."""
        land = self.land
        if self._land_arrays is None:
            coarse, clear, coarse_deg = coarse_land(land)
            self._land_arrays = (coarse, clear, coarse_deg, np.asarray(land.raster),
                                 np.asarray(land.coast_distance))
        coarse, clear, coarse_deg, raster, coast_dist = self._land_arrays
        fine = land.fine_coast
        ends = [np.ascontiguousarray(e, dtype=float) for e in (lon0, lat0, lon1, lat1)]
        out = np.empty(ends[0].size, dtype=np.int64)
        todo = np.arange(out.size)
        while todo.size:
            x0, y0, x1, y1 = [e[todo] for e in ends]
            got = np.empty(todo.size, dtype=np.int64)
            misses: list[np.ndarray] = []

            def scan(a: int, b: int, x0: np.ndarray = x0, y0: np.ndarray = y0,
                     x1: np.ndarray = x1, y1: np.ndarray = y1, got: np.ndarray = got,
                     misses: list[np.ndarray] = misses) -> None:
                buf = np.empty(MISS_BUFFER, dtype=np.int64)
                n = rk.ga_land_hits(x0[a:b], y0[a:b], x1[a:b], y1[a:b], coarse, clear,
                                    coarse_deg, raster, coast_dist, land.cell_deg,
                                    self.spacing_deg, fine.keys, fine.fine, buf, got[a:b])
                misses.append(buf[:n])

            in_chunks(todo.size, scan)
            out[todo] = got
            if any(m.size for m in misses):
                fine.add(np.concatenate(misses))
            todo = todo[got < 0]
        return out

    @staticmethod
    def _exact_hits(lon0: np.ndarray, lat0: np.ndarray, lon1: np.ndarray, lat1: np.ndarray
                    ) -> np.ndarray:
        """Points on full-resolution land (polygons) of segments sampled every 0.25 NM along
        the geodesic, both ends included (`densify_track` of each segment, all at once)."""
        from shiproute_core.geodesy import direct, inverse

        from ..geo.full_land import final_land
        from .land_repair import STEP_M

        az, dist = inverse(lon0, lat0, lon1, lat1)
        n = np.maximum(1, np.ceil(dist / STEP_M).astype(np.int64))
        seg = np.repeat(np.arange(lon0.size), n)
        first = np.concatenate([[0], np.cumsum(n)[:-1]])
        frac = (np.arange(seg.size) - first[seg] + 1) / n[seg]
        lon, lat = direct(lon0[seg], lat0[seg], az[seg], dist[seg] * frac)
        on = final_land().contains(np.concatenate([lon0, lon]), np.concatenate([lat0, lat]))
        along = np.bincount(seg, weights=on[lon0.size:], minlength=lon0.size)
        return on[:lon0.size].astype(np.int64) + np.rint(along).astype(np.int64)


def level1_reach_nm(rule: ClearanceRule) -> float:
    """The level-0 distance to the coast [NM] below which a walk with `rule` may read level 1
    (where the tiles to build beforehand lie)."""
    return max(rule.open_sea_nm, rule.approach_nm) + lw.L0_MIN_JUMP_NM


# round a voyage's ports: where its seeds go (great circles via points 12 deg off it, the
# sea lane; the intermediate coastline's cells are resolved over the same box)
REGION_MARGINS_DEG = (10.0, 10.0, 15.0, 25.0)  # west, east, south, north


def build_region_tiles(a: tuple[float, float], b: tuple[float, float],
                       margins_deg: tuple[float, float, float, float],
                       rule: ClearanceRule) -> int:
    """Build and save the level-1 tiles a walk with `rule` can read in the box between `a`
    and `b` ((lon, lat) [deg]; the shorter way round in longitude) widened by (west, east,
    south, north) margins [deg]: a first plan on a fresh machine then searches instead of
    building tiles. How many were new."""
    from ..geo.fine_distance import default_fine_distance
    from ..geo.full_land import final_land
    from ..geo.region_box import region_box

    finest = final_land().mask
    fine = default_fine_distance()
    built = fine.add_box(*region_box(a, b, margins_deg), np.asarray(finest.coast_distance),
                         finest.cell_deg, level1_reach_nm(rule) + 0.1)
    fine.save()
    return built


def coarse_land(land: LandMask) -> tuple[np.ndarray, np.ndarray, float]:
    """The land scan's near-land filter of `land` (built once per mask): the coarse raster
    (`COARSE_FACTOR` cells, land or coast in or next to a block), per block the arc [deg] to
    the nearest flagged block, the larger of the polar-shrink bound and each latitude band's
    (`geo.clear_distance`; about 1.4 times the polar jumps along mid-latitude routes, the
    same samples decide), and the block size [deg]."""
    key = id(land)
    coarse_deg = land.cell_deg * COARSE_FACTOR
    if key not in _COARSE:
        coarse = fk.coarse_land_raster(np.asarray(land.raster), COARSE_FACTOR)
        # both are lower bounds of the arc to land: so is the larger (the banded one is
        # capped at its reach, the polar one is not)
        clear = np.maximum(banded_clear_distance_deg(coarse, coarse_deg),
                           fk.clear_distance_deg(coarse, coarse_deg))
        _COARSE[key] = (coarse, np.ascontiguousarray(clear))
    coarse, clear = _COARSE[key]
    return coarse, clear, coarse_deg
