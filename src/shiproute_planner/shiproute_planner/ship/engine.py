"""Main-engine fuel rate and limit checks (SFOC curve vs load, speed, power and torque)."""

from __future__ import annotations

import numpy as np

from .spec import EngineSpec


def sfoc_g_per_kwh(engine: EngineSpec, load: np.ndarray) -> np.ndarray:
    """SFOC at engine load (fraction of MCR), linear in the file's curve, flat outside it."""
    return np.interp(load, engine.sfoc_load_fraction, engine.sfoc_g_per_kwh)


def fuel_t_per_h(engine: EngineSpec, brake_power_kw: np.ndarray) -> np.ndarray:
    """Fuel mass flow (t/h) = P_B * SFOC."""
    load = brake_power_kw / engine.mcr_kw
    return brake_power_kw * sfoc_g_per_kwh(engine, load) * 1e-6


def limit_exceeded(engine: EngineSpec, rpm: np.ndarray, brake_power_kw: np.ndarray) -> np.ndarray:
    """True where RPM is out of range, power exceeds the overload limit or torque its limit."""
    torque_ratio = (brake_power_kw / engine.mcr_kw) * (engine.rpm_mcr / np.maximum(rpm, 1e-9))
    return (
        (rpm < engine.rpm_min)
        | (rpm > engine.rpm_max)
        | (brake_power_kw > engine.overload_power_fraction * engine.mcr_kw)
        | (torque_ratio > engine.torque_limit_fraction)
    )
