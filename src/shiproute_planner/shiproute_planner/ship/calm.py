"""Calm-water RPM curve of a ship (speed, brake power, fuel vs RPM), tabulated once."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .physics import PhysicsModel
from .seastate import SeaState


@dataclass(frozen=True)
class CalmCurve:
    """Calm-water speed through water, brake power and fuel on an RPM grid (monotone)."""

    rpm: np.ndarray
    stw_m_s: np.ndarray
    brake_power_kw: np.ndarray
    fuel_t_per_h: np.ndarray

    def at_rpm(self, rpm: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(speed, brake power, fuel) at ``rpm`` by linear interpolation."""
        return (
            np.interp(rpm, self.rpm, self.stw_m_s),
            np.interp(rpm, self.rpm, self.brake_power_kw),
            np.interp(rpm, self.rpm, self.fuel_t_per_h),
        )

    def rpm_at_speed(self, stw_m_s: np.ndarray) -> np.ndarray:
        """Inverse: RPM giving ``stw_m_s`` in calm water."""
        return np.interp(stw_m_s, self.stw_m_s, self.rpm)


def calm_curve(physics: PhysicsModel, n_points: int = 400) -> CalmCurve:
    """Tabulate the physics model in calm water from 1 rpm to 1.5 x the engine's max RPM."""
    rpm = np.linspace(1.0, 1.5 * physics.ship.engine.rpm_max, n_points)
    r = physics.evaluate(rpm, 0.0, SeaState.calm())
    return CalmCurve(rpm, r.stw_m_s, r.brake_power_kw, r.fuel_t_per_h)
