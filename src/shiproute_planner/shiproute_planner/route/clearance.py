"""The clearance from the coast a route keeps: per sea-area type, as the optimiser's constraint.

Open sea keeps `open_sea_nm`; within `approach_zone_nm` of either end of the optimised span
(port or pilot station, strait passage exit, the ship's position on a re-plan) the route keeps
`approach_nm`; within `approach_nm` + `FREE_MARGIN_NM` of an end only land itself counts
(pilot stations and a ship's position can lie close to shore). The default keeps off land
only: with the issue's 2 NM open sea / 0.5 NM near the ends, narrow passages farther than
the zone from a span end (Uraga Suido into Tokyo Bay, the Kanmon Strait) close, and voyages
through them end infeasible until straits get a clearance of their own.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError

FREE_MARGIN_NM = 0.5
EPS_NM = 0.05  # the walk's step where a route hugs its clearance (it keeps c - EPS_NM)
OPEN_SEA_RANGE_NM = (0.0, 5.0)
APPROACH_RANGE_NM = (0.0, 3.0)
APPROACH_ZONE_RANGE_NM = (0.0, 200.0)


@dataclass(frozen=True)
class ClearanceRule:
    """Distances from land [NM] a route keeps, by where it is."""

    open_sea_nm: float = 0.0
    approach_nm: float = 0.0
    approach_zone_nm: float = 10.0

    def __post_init__(self) -> None:
        for name, (lo, hi) in (("open_sea_nm", OPEN_SEA_RANGE_NM),
                               ("approach_nm", APPROACH_RANGE_NM),
                               ("approach_zone_nm", APPROACH_ZONE_RANGE_NM)):
            value = getattr(self, name)
            if not (isinstance(value, int | float) and math.isfinite(value)
                    and lo <= value <= hi):
                raise ParameterError(f"clearance {name} must be a number in {lo:g}..{hi:g} "
                                     f"NM, got {value!r}")

    @property
    def free_radius_nm(self) -> float:
        """Radius [NM] round a span end within which only land counts."""
        return self.approach_nm + FREE_MARGIN_NM

    def kernel_array(self) -> np.ndarray:
        """The walk's rule array (`route._land_walk.clearance_walk`)."""
        return np.array([self.open_sea_nm, self.approach_nm, self.approach_zone_nm,
                         self.free_radius_nm, EPS_NM])

    @property
    def words(self) -> str:
        """The rule in words, as a plan states it."""
        if self.open_sea_nm == 0.0 and self.approach_nm == 0.0:
            return "no clearance (off land only)"
        return (f"clearance {self.open_sea_nm:g} NM open sea / {self.approach_nm:g} NM within "
                f"{self.approach_zone_nm:g} NM of the span ends")
