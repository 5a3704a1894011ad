"""Added resistance of wind (ISO 15016:2015 form) with tabulated longitudinal coefficients.

R_AA = 1/2 rho_air C_AA(psi_rel) A_XV V_rel^2 - 1/2 rho_air C_AA(0) A_XV V_stw^2: the wind
load at the relative wind minus the still-air resistance the ship already has in the
calm-water (trial) baseline. The coefficient tables C_AA(psi) play the role of the ISO
15016 Annex C data sets; bundled sets are generated from Blendermann's (1994) parametric
ship-type model; a ship file may give its own wind-tunnel or STA-JIP table instead.
"""

from __future__ import annotations

import numpy as np

RHO_AIR_KG_M3 = 1.225

# Blendermann (1994), "Parameter identification of wind loads on ships", J. Wind Eng. 51:
# ship type -> (CD_t, CD_l_AF(0), CD_l_AF(pi), delta)
_BLENDERMANN: dict[str, tuple[float, float, float, float]] = {
    "blendermann_container_loaded": (0.90, 0.55, 0.55, 0.40),
    "blendermann_cargo_loaded": (0.85, 0.65, 0.55, 0.40),
    "blendermann_tanker_loaded": (0.70, 0.90, 0.55, 0.40),
    "blendermann_tanker_ballast": (0.70, 0.75, 0.55, 0.40),
}

TABLE_ANGLES_DEG = tuple(float(a) for a in range(0, 181, 10))


def coefficient_sets() -> list[str]:
    """Names of the built-in wind coefficient sets."""
    return sorted(_BLENDERMANN)


def blendermann_caa(set_name: str, frontal_area_m2: float, lateral_area_m2: float) -> np.ndarray:
    """C_AA on ``TABLE_ANGLES_DEG`` (resistance positive, based on the frontal area A_XV)."""
    cd_t, cdl0, cdlpi, delta = _BLENDERMANN[set_name]
    eps = np.radians(np.asarray(TABLE_ANGLES_DEG))
    cdl_af = np.where(eps <= np.pi / 2, cdl0, cdlpi)
    cdl = cdl_af * frontal_area_m2 / lateral_area_m2
    denom = 1.0 - 0.5 * delta * (1.0 - cdl / cd_t) * np.sin(2.0 * eps) ** 2
    cx = -cdl * (lateral_area_m2 / frontal_area_m2) * np.cos(eps) / denom
    return -cx  # force along -x (aft) is resistance


def relative_wind(
    stw_m_s: np.ndarray, heading_deg: np.ndarray, wind_u_m_s: np.ndarray, wind_v_m_s: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Relative wind speed (m/s) and angle off the bow (deg, 0 = head, 0..180)."""
    h = np.radians(heading_deg)
    sh, ch = np.sin(h), np.cos(h)
    # air velocity relative to the ship, in ship axes (x forward, y starboard)
    ax = wind_u_m_s * sh + wind_v_m_s * ch - stw_m_s
    ay = wind_u_m_s * ch - wind_v_m_s * sh
    speed = np.hypot(ax, ay)
    angle = np.degrees(np.arctan2(np.abs(ay), -ax))  # 0 when air comes from ahead
    return speed, angle


def wind_resistance_n(
    stw_m_s: np.ndarray,
    rel_speed_m_s: np.ndarray,
    rel_angle_deg: np.ndarray,
    frontal_area_m2: float,
    table_angle_deg: np.ndarray,
    table_caa: np.ndarray,
) -> np.ndarray:
    """ISO 15016 wind added resistance (N); negative for a following wind."""
    caa = np.interp(rel_angle_deg, table_angle_deg, table_caa)
    q = 0.5 * RHO_AIR_KG_M3 * frontal_area_m2
    return q * (caa * rel_speed_m_s**2 - table_caa[0] * stw_m_s**2)
