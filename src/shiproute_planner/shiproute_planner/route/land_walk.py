"""The land test of every evaluated route: the clearance walk of one problem's legs.

One object per problem holds what `_land_walk.clearance_walk` reads (the finest coastline's
coarse clear distances and level 0, the shared level-1 tiles, the problem's clearance rule
and span ends); `segments` walks legs on the planner's threads, builds the tiles the walk
met for the first time and walks those legs again, so a verdict never depends on which
tiles earlier plans built. The GA's evaluator and the exact one call the same test.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from ..chunks import in_chunks
from . import _land_walk as lw
from .problem import RouteProblem

MISS_BUFFER = 4096  # unbuilt level-1 tiles one walk may report
Work = Callable[[int, int], None]


class LandWalk:
    """The clearance walk of one problem (see the module docstring)."""

    def __init__(self, problem: RouteProblem) -> None:
        from ..geo.fine_distance import default_fine_distance
        from ..geo.full_land import final_land
        from .fast_eval import coarse_land

        finest = final_land().mask
        self.coarse, self.clear, self.coarse_deg = coarse_land(finest)
        self.coast_dist = np.asarray(finest.coast_distance)
        self.cell_deg = finest.cell_deg
        self.fine = default_fine_distance()
        self.spacing_deg = problem.land_spacing_deg
        self.rule = problem.limits.clearance.kernel_array()
        self.ends = np.array([*lw.unit_vector(problem.dep_lat_deg, problem.dep_lon_deg),
                              *lw.unit_vector(problem.arr_lat_deg, problem.arr_lon_deg)])

    def segments(self, lon0: np.ndarray, lat0: np.ndarray, lon1: np.ndarray,
                 lat1: np.ndarray, alongside: Work | None = None) -> np.ndarray:
        """Violations of great-circle segments (any shape; 0 = clear): samples on land or
        closer to the coast than the rule allows. `alongside(a, b)`: work on segments a..b
        run in the first pass's threads (one fan-out for both)."""
        shape = np.shape(lon0)
        ends = [np.ascontiguousarray(e, dtype=float).ravel() for e in (lon0, lat0, lon1, lat1)]
        out = np.empty(ends[0].size, dtype=np.int64)
        todo = np.arange(out.size)
        first = True
        while todo.size:
            x0, y0, x1, y1 = ends if first else [e[todo] for e in ends]
            got = np.empty(todo.size, dtype=np.int64)
            misses: list[np.ndarray] = []
            slots, grids = self.fine.slots, self.fine.grids  # one consistent pair per pass

            def walk(a: int, b: int, x0: np.ndarray = x0, y0: np.ndarray = y0,
                     x1: np.ndarray = x1, y1: np.ndarray = y1, got: np.ndarray = got,
                     misses: list[np.ndarray] = misses, extra: Work | None = alongside,
                     slots: np.ndarray = slots, grids: np.ndarray = grids) -> None:
                buf = np.empty(MISS_BUFFER, dtype=np.int64)
                n = lw.clearance_walk(x0[a:b], y0[a:b], x1[a:b], y1[a:b], self.coarse,
                                      self.clear, self.coarse_deg, self.coast_dist,
                                      self.cell_deg, self.spacing_deg, slots, grids, self.ends,
                                      self.rule, buf, got[a:b])
                misses.append(buf[:n])
                if extra is not None:
                    extra(a, b)

            in_chunks(todo.size, walk)
            out[todo] = got
            if any(m.size for m in misses):
                self.fine.add(np.concatenate(misses))
            todo = todo[got < 0]
            first, alongside = False, None
        return out.reshape(shape)
