"""Inputs shared by every baseline run: the voyage problem, environment, land and seeds."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from shiproute_core.geodesy import inverse

from ..geo.landmask import LandMask
from ..route.environment import Environment
from ..route.problem import RouteProblem
from ..route.seeding import TrackSeed
from .context import PlannerLegSailor
from .errors import BaselineConfigError

# useful band of calm-water speed, as a share of the speed that sails the great circle in the
# allowed time: slower cannot make the RTA, faster only burns fuel (storm detours included)
LOW_SPEED_SHARE = 0.75
HIGH_SPEED_SHARE = 1.2


@dataclass(frozen=True)
class BaselineInputs:
    """Problem + environment + land mask, and seeds for the seeded metaheuristics.

    `seed_tracks` are extra seed polylines (pool, previous plan) as the planner passes them;
    `seed_genes`, when given, are the seeds already converted to genes (saves recomputing
    them for every run of a comparison).
    """

    problem: RouteProblem
    env: Environment
    land: LandMask
    seed_tracks: tuple[TrackSeed, ...] = ()
    seed_genes: np.ndarray | None = field(default=None, repr=False)

    def sailor(self) -> PlannerLegSailor:
        return PlannerLegSailor(self.problem, self.env, self.land)

    def required_speed_m_s(self) -> float:
        """Great-circle distance over the time allowed."""
        p = self.problem
        _, dist = inverse(p.dep_lon_deg, p.dep_lat_deg, p.arr_lon_deg, p.arr_lat_deg)
        return float(dist) / (p.rta_s - p.depart_s)

    def rpm_levels(self, n: int, low_share: float = LOW_SPEED_SHARE,
                   high_share: float = HIGH_SPEED_SHARE) -> np.ndarray:
        """`n` evenly spaced RPMs whose calm-water speeds span the useful band.

        The band runs from `low_share` to `high_share` of the speed that sails the great
        circle in the allowed time, clamped to the engine's RPM range.
        """
        if n < 2:
            raise BaselineConfigError(f"need at least 2 RPM levels, got {n}")
        lim = self.problem.limits
        probe = np.linspace(lim.rpm_min, lim.rpm_max, 128)
        speeds = self.sailor().calm_speed_m_s(probe)
        need = self.required_speed_m_s()
        low = float(np.interp(low_share * need, speeds, probe))
        high = float(np.interp(high_share * need, speeds, probe))
        low, high = max(low, lim.rpm_min), min(high, lim.rpm_max)
        if not high > low:
            low, high = lim.rpm_min, lim.rpm_max
        return np.linspace(low, high, n)
