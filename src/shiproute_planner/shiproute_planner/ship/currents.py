"""Speed and course over ground from speed through water, heading and surface current."""

from __future__ import annotations

import numpy as np


def over_ground(
    stw_m_s: np.ndarray,
    heading_deg: np.ndarray,
    current_u_m_s: np.ndarray,
    current_v_m_s: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """SOG (m/s) and COG (deg true, 0..360) as the vector sum of ship and current velocity."""
    h = np.radians(heading_deg)
    east = stw_m_s * np.sin(h) + current_u_m_s
    north = stw_m_s * np.cos(h) + current_v_m_s
    return np.hypot(east, north), np.degrees(np.arctan2(east, north)) % 360.0
