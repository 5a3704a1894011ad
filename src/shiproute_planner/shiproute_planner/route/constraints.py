"""Per-leg constraint flags (bits from shiproute_core.flags) and violation measures.

Violations are non-negative and dimensionless so they can be summed for Deb's
feasibility-first rules: land in land samples, lateness in hours, seakeeping as relative
excess over the criterion, limits as relative excess, flags as counts of legs.
"""

from __future__ import annotations

import numpy as np
from shiproute_core.flags import (
    FLAG_DECK_WETNESS,
    FLAG_DEPTH,
    FLAG_ENGINE_LIMIT,
    FLAG_HEADING_CHANGE,
    FLAG_IMO_HIGH_WAVE_GROUP,
    FLAG_IMO_PARAMETRIC_ROLL,
    FLAG_IMO_SURF_RIDING,
    FLAG_IMO_SYNCHRONOUS_ROLL,
    FLAG_LAND,
    FLAG_LATITUDE,
    FLAG_NO_GO_ZONE,
    FLAG_PROPELLER_EMERGENCE,
    FLAG_RPM_RANGE,
    FLAG_SLAMMING,
    FLAG_WAVE_LIMIT,
    FLAG_WIND_LIMIT,
)

from .problem import RouteLimits


def _excess(value: np.ndarray, limit: float) -> np.ndarray:
    return np.maximum(0.0, np.nan_to_num(value) - limit) / max(limit, 1e-9)


def leg_flags_and_violation(
    legs: dict[str, np.ndarray], limits: RouteLimits, active: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Per-leg flag bitmask (pop, m) and violation (pop, m) from per-leg arrays.

    `legs` holds LegPerformance fields plus `land_samples`, `turn_deg` and `rpm`; `active`
    masks legs of non-zero length (padding legs of shorter tracks are ignored).
    """
    shape = legs["rpm"].shape
    flags = np.zeros(shape, dtype=np.uint32)
    viol = np.zeros(shape)

    def add(mask: np.ndarray, bit: int, amount: np.ndarray | float) -> None:
        nonlocal viol
        mask = mask & active
        flags[mask] |= np.uint32(bit)
        viol = viol + np.where(mask, amount, 0.0)

    land = legs["land_samples"]
    add(land > 0, FLAG_LAND, 1.0 + land)
    for key, bit, crit in (
        ("p_slamming", FLAG_SLAMMING, limits.p_slamming_max),
        ("p_deck_wetness", FLAG_DECK_WETNESS, limits.p_deck_wetness_max),
        ("p_propeller_emergence", FLAG_PROPELLER_EMERGENCE, limits.p_propeller_emergence_max),
    ):
        ex = _excess(legs[key], crit)
        add(ex > 0, bit, ex)
    turn = np.abs(legs["turn_deg"])
    ex = _excess(turn, limits.max_heading_change_deg)
    add(ex > 1e-9, FLAG_HEADING_CHANGE, ex)
    rpm = legs["rpm"]
    out = (rpm < limits.rpm_min - 1e-9) | (rpm > limits.rpm_max + 1e-9)
    add(out, FLAG_RPM_RANGE, np.abs(rpm - np.clip(rpm, limits.rpm_min, limits.rpm_max)))
    if limits.max_hs_m is not None:
        ex = _excess(legs["hs_m"], limits.max_hs_m)
        add(ex > 0, FLAG_WAVE_LIMIT, ex)
    if limits.max_wind_m_s is not None:
        ex = _excess(legs["wind_speed_m_s"], limits.max_wind_m_s)
        add(ex > 0, FLAG_WIND_LIMIT, ex)
    for key, bit in (
        ("surf_riding", FLAG_IMO_SURF_RIDING),
        ("parametric_roll", FLAG_IMO_PARAMETRIC_ROLL),
        ("synchronous_roll", FLAG_IMO_SYNCHRONOUS_ROLL),
        ("high_wave_group", FLAG_IMO_HIGH_WAVE_GROUP),
    ):
        if key in limits.imo_checks:
            add(np.asarray(legs[key], dtype=bool), bit, 1.0)
    if limits.engine_limit:
        add(np.asarray(legs["engine_limit_exceeded"], dtype=bool), FLAG_ENGINE_LIMIT, 1.0)
    if "ukc_m" in legs:  # metres short of the required depth (NaN: depth unknown)
        short = np.maximum(0.0, -np.nan_to_num(legs["ukc_m"], nan=0.0))
        add(short > 0, FLAG_DEPTH, 1.0 + short)
    if "zone_nm" in legs:  # NM sailed inside hard no-go zones
        add(legs["zone_nm"] > 0, FLAG_NO_GO_ZONE, 1.0 + legs["zone_nm"])
    lat_ex = np.maximum(0.0, np.abs(legs["lat_end_deg"]) - limits.lat_bound_deg)
    add(lat_ex > 0, FLAG_LATITUDE, lat_ex)
    return flags, viol
