"""Result type and the interface every ship performance model implements."""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Protocol, runtime_checkable

import numpy as np

from .seastate import SeaState
from .spec import ShipSpec


@dataclass(frozen=True)
class LegPerformance:
    """Per-leg results, all arrays of the broadcast input shape (SI; fuel in t/h)."""

    stw_m_s: np.ndarray
    sog_m_s: np.ndarray
    cog_deg: np.ndarray
    brake_power_kw: np.ndarray
    fuel_t_per_h: np.ndarray
    engine_load: np.ndarray  # brake power / MCR
    engine_limit_exceeded: np.ndarray  # bool: rpm range, power or torque limit
    p_slamming: np.ndarray
    p_deck_wetness: np.ndarray
    p_propeller_emergence: np.ndarray
    surf_riding: np.ndarray  # bool, IMO MSC.1/Circ.1228
    parametric_roll: np.ndarray  # bool
    synchronous_roll: np.ndarray  # bool
    high_wave_group: np.ndarray  # bool, successive high-wave attack
    hs_m: np.ndarray
    wind_speed_m_s: np.ndarray

    def as_dict(self) -> dict[str, np.ndarray]:
        """Field name -> array."""
        return {f.name: getattr(self, f.name) for f in fields(self)}


@runtime_checkable
class PerformanceModel(Protocol):
    """RPM + heading + environment -> speed, power, fuel and seakeeping (vectorised)."""

    ship: ShipSpec

    def evaluate(
        self, rpm: np.ndarray, heading_deg: np.ndarray, sea: SeaState
    ) -> LegPerformance:
        """Evaluate legs; inputs broadcast to one shape."""
        ...

    def rpm_for_speed(
        self, stw_m_s: np.ndarray, heading_deg: np.ndarray, sea: SeaState
    ) -> np.ndarray:
        """Engine RPM that gives the requested speed through water."""
        ...
