"""Inputs shared by every baseline run: the voyage problem, environment, land and seeds."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..geo.landmask import LandMask
from ..route.environment import Environment
from ..route.problem import RouteProblem
from .context import PlannerLegSailor
from .errors import BaselineConfigError


@dataclass(frozen=True)
class BaselineInputs:
    """Problem + environment + land mask, plus seeds (genes) for the seeded metaheuristics."""

    problem: RouteProblem
    env: Environment
    land: LandMask | None
    seeds: np.ndarray | None = field(default=None, repr=False)

    def sailor(self) -> PlannerLegSailor:
        return PlannerLegSailor(self.problem, self.env, self.land)

    def rpm_levels(self, n: int, low_fraction: float = 0.6) -> np.ndarray:
        """`n` evenly spaced RPM levels from a useful minimum to the maximum RPM.

        The lowest level is the RPM whose calm-water speed is `low_fraction` of the speed that
        covers the great circle in the allowed time (slower is never useful to meet the RTA
        except in a strong following current), clamped to the engine range.
        """
        if n < 2:
            raise BaselineConfigError(f"need at least 2 RPM levels, got {n}")
        lim = self.problem.limits
        sailor = self.sailor()
        probe = np.linspace(lim.rpm_min, lim.rpm_max, 64)
        speeds = sailor.calm_speed_m_s(probe)
        from .geodesy import inverse

        _, dist = inverse(self.problem.dep_lon_deg, self.problem.dep_lat_deg,
                          self.problem.arr_lon_deg, self.problem.arr_lat_deg)
        need = float(dist) / (self.problem.rta_s - self.problem.depart_s)
        low = float(np.interp(low_fraction * need, speeds, probe))
        return np.linspace(max(low, lim.rpm_min), lim.rpm_max, n)
