"""Units and physical constants: SI inside, knots and nautical miles only at the edges."""

from __future__ import annotations

M_PER_NM = 1852.0  # international nautical mile
S_PER_HOUR = 3600.0
S_PER_DAY = 86_400.0
M_S_PER_KNOT = M_PER_NM / S_PER_HOUR  # 1 knot = 1 NM per hour
G_M_S2 = 9.80665  # standard gravity
KG_PER_TONNE = 1000.0


def knots_to_m_s(speed_kn: float) -> float:
    """Speed in knots -> m/s."""
    return speed_kn * M_S_PER_KNOT


def m_s_to_knots(speed_m_s: float) -> float:
    """Speed in m/s -> knots."""
    return speed_m_s / M_S_PER_KNOT


def nm_to_m(distance_nm: float) -> float:
    """Distance in nautical miles -> metres."""
    return distance_nm * M_PER_NM


def m_to_nm(distance_m: float) -> float:
    """Distance in metres -> nautical miles."""
    return distance_m / M_PER_NM
