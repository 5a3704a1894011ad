"""`LegSailor` backed by the planner's own leg sailing, ship model, land mask and limits.

Graph baselines search with exactly the physics and constraint rules the seed GA is judged
by: `route.legs.sail_to` (weather met at the leg start, heading corrected for current),
`route.constraints.leg_flags_and_violation` for seakeeping/IMO/engine limits, and the
planner's `LandMask` with the problem's land sampling spacing. Nothing here models the ship.
"""

from __future__ import annotations

import functools

import numpy as np
from shiproute_core.flags import FLAG_HEADING_CHANGE, FLAG_LAND
from shiproute_core.geodesy import direct, inverse

from ..geo.landmask import LandMask
from ..route.constraints import leg_flags_and_violation
from ..route.environment import Environment
from ..route.evaluation import clear_ports
from ..route.land_walk import LandWalk
from ..route.legs import perf_arrays, sail_to
from ..route.problem import RouteProblem
from .legs import LegBatch

_SEARCH_IGNORED_FLAGS = np.uint32(FLAG_LAND | FLAG_HEADING_CHANGE)  # land is tested separately


class PlannerLegSailor:
    """Vectorised legs for the graph baselines, evaluated like the planner's routes."""

    def __init__(self, problem: RouteProblem, env: Environment, land: LandMask | None) -> None:
        self.problem = problem
        self.env = env
        self.land = land
        self.evaluations = 0

    def _batch(
        self,
        arrays: dict[str, np.ndarray],
        rpm: np.ndarray,
        lon1: np.ndarray,
        lat1: np.ndarray,
        dist: np.ndarray,
        duration: np.ndarray,
    ) -> LegBatch:
        shape = duration.shape
        legs = dict(arrays)
        legs["rpm"] = np.broadcast_to(rpm, shape).astype(float)
        legs["land_samples"] = np.zeros(shape, dtype=np.int64)
        legs["turn_deg"] = np.zeros(shape)
        legs["lat_end_deg"] = np.asarray(lat1, dtype=float)
        flags, _ = leg_flags_and_violation(legs, self.problem.limits, np.ones(shape, dtype=bool))
        ok = (flags & ~_SEARCH_IGNORED_FLAGS) == 0
        fuel = arrays["fuel_t_per_h"] * duration / 3600.0
        self.evaluations += int(duration.size)
        return LegBatch(np.asarray(lon1, float), np.asarray(lat1, float), dist, duration,
                        fuel, arrays["sog_m_s"], ok)

    def between(self, lon0_deg, lat0_deg, lon1_deg, lat1_deg, t0_s, rpm) -> LegBatch:
        """Sail point 0 -> point 1 at `rpm` from `t0_s` (planner's `sail_to`)."""
        rpm = np.asarray(rpm, dtype=float)
        arrays, _, dist, duration = sail_to(
            self.env, np.asarray(lon0_deg, float), np.asarray(lat0_deg, float),
            np.asarray(t0_s, float), np.asarray(lon1_deg, float), np.asarray(lat1_deg, float), rpm,
        )
        return self._batch(arrays, rpm, lon1_deg, lat1_deg, dist, duration)

    def for_duration(self, lon0_deg, lat0_deg, heading_deg, t0_s, rpm, duration_s) -> LegBatch:
        """Steer `heading_deg` at `rpm` for `duration_s`; the track follows COG at SOG."""
        lon0 = np.asarray(lon0_deg, float)
        lat0 = np.asarray(lat0_deg, float)
        rpm = np.asarray(rpm, dtype=float)
        sea = self.env.sea_state(lon0, lat0, np.asarray(t0_s, float))
        perf = self.env.perform(rpm, np.asarray(heading_deg, float), sea)
        arrays = perf_arrays(perf, lon0.shape)
        dist = arrays["sog_m_s"] * duration_s
        lon1, lat1 = direct(lon0, lat0, arrays["cog_deg"], dist)
        duration = np.full(lon0.shape, float(duration_s))
        return self._batch(arrays, rpm, lon1, lat1, dist, duration)

    def on_land(self, lon_deg, lat_deg) -> np.ndarray:
        if self.land is None:
            return np.zeros(np.shape(lon_deg), dtype=bool)
        return np.asarray(self.land.is_land(lon_deg, lat_deg), dtype=bool)

    def crosses_land(self, lon0_deg, lat0_deg, lon1_deg, lat1_deg) -> np.ndarray:
        if self.land is None:
            return np.zeros(np.shape(lon0_deg), dtype=bool)
        shape = np.shape(lon0_deg)
        lon = np.column_stack([np.ravel(lon0_deg), np.ravel(lon1_deg)]).astype(float)
        lat = np.column_stack([np.ravel(lat0_deg), np.ravel(lat1_deg)]).astype(float)
        _, dist = inverse(lon[:, 0], lat[:, 0], lon[:, 1], lat[:, 1])
        # the evaluator's own port clearance, so search and final evaluation agree exactly
        a_lon, a_lat, b_lon, b_lat = clear_ports(self.problem, lon, lat, dist[:, None])
        # and its land test: the finest coastline with the problem's clearance
        samples = self._walk.segments(a_lon, a_lat, b_lon, b_lat)
        return (np.asarray(samples) > 0).reshape(shape)

    @functools.cached_property
    def _walk(self) -> LandWalk:
        """The evaluator's land test of this problem (`route.land_walk`)."""
        return LandWalk(self.problem, self.land, exact_tight=True)

    def _calm(self, rpm: np.ndarray):
        from ..ship import SeaState

        rpm = np.asarray(rpm, dtype=float)
        return self.env.model.evaluate(rpm, np.zeros(rpm.shape), SeaState.calm(rpm.shape))

    def calm_speed_m_s(self, rpm) -> np.ndarray:
        return np.asarray(self._calm(rpm).stw_m_s, dtype=float)

    def calm_fuel_t_per_h(self, rpm) -> np.ndarray:
        return np.asarray(self._calm(rpm).fuel_t_per_h, dtype=float)
