"""The leg-level interface the graph baselines search with, so every method sails legs the same way.

A graph method (isochrone, Dijkstra/A*, 3DDP, time-constrained A*, two-stage DP) only needs to
know, for many candidate legs at once, how long a leg takes, how much fuel it burns and whether
it breaks a constraint. `LegSailor` is that question; `context.PlannerLegSailor` answers it with
the planner's own ship model, weather sampler, land mask and constraint limits.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np


@dataclass(frozen=True)
class LegBatch:
    """Results for a batch of legs (all arrays one shape); SI units, fuel in tonnes."""

    end_lon_deg: np.ndarray
    end_lat_deg: np.ndarray
    distance_m: np.ndarray
    duration_s: np.ndarray
    fuel_t: np.ndarray
    sog_m_s: np.ndarray
    ok: np.ndarray  # bool: no land, seakeeping and engine limits respected on this leg


class LegSailor(Protocol):
    """Vectorised leg evaluation shared by the graph baselines."""

    def between(
        self,
        lon0_deg: np.ndarray,
        lat0_deg: np.ndarray,
        lon1_deg: np.ndarray,
        lat1_deg: np.ndarray,
        t0_s: np.ndarray,
        rpm: np.ndarray,
    ) -> LegBatch:
        """Sail from point 0 to point 1 at constant `rpm`, leaving at `t0_s`."""
        ...

    def for_duration(
        self,
        lon0_deg: np.ndarray,
        lat0_deg: np.ndarray,
        heading_deg: np.ndarray,
        t0_s: np.ndarray,
        rpm: np.ndarray,
        duration_s: float,
    ) -> LegBatch:
        """Sail on a constant `heading_deg` at `rpm` for `duration_s` from `t0_s`."""
        ...

    def on_land(self, lon_deg: np.ndarray, lat_deg: np.ndarray) -> np.ndarray:
        """True where a point is on land."""
        ...

    def crosses_land(
        self,
        lon0_deg: np.ndarray,
        lat0_deg: np.ndarray,
        lon1_deg: np.ndarray,
        lat1_deg: np.ndarray,
    ) -> np.ndarray:
        """True where the segment between the two points touches land."""
        ...

    def calm_speed_m_s(self, rpm: np.ndarray) -> np.ndarray:
        """Speed through water in calm water at `rpm` (for heuristics and initial guesses)."""
        ...

    def calm_fuel_t_per_h(self, rpm: np.ndarray) -> np.ndarray:
        """Fuel rate in calm water at `rpm` (for heuristics)."""
        ...
