"""Input range checks shared by all models (clear errors instead of silent garbage)."""

from __future__ import annotations

import numpy as np

from .errors import InputRangeError
from .seastate import SeaState
from .spec import ShipSpec

MAX_HS_M = 25.0
MAX_WIND_M_S = 80.0
MAX_CURRENT_M_S = 6.0
PERIOD_RANGE_S = (0.5, 30.0)


def check_range(name: str, a: np.ndarray, lo: float, hi: float) -> None:
    """Raise ``InputRangeError`` if ``a`` has NaN or values outside [lo, hi]."""
    a = np.asarray(a)
    if a.size == 0:
        return
    if not np.all(np.isfinite(a)):
        raise InputRangeError(name, "contains NaN or infinite values")
    mn, mx = float(a.min()), float(a.max())
    if mn < lo or mx > hi:
        raise InputRangeError(name, f"values {mn:.4g}..{mx:.4g} outside the valid range {lo}..{hi}")


def check_inputs(ship: ShipSpec, rpm: np.ndarray, heading_deg: np.ndarray, sea: SeaState) -> None:
    """Validate RPM, heading and sea state for ``evaluate``."""
    check_range("rpm", rpm, 1e-6, 1.5 * ship.engine.rpm_max)
    check_range("heading_deg", heading_deg, -720.0, 720.0)
    check_sea(sea)


def check_sea(sea: SeaState) -> None:
    """Validate a sea state (wave heights, periods, wind and current speeds)."""
    check_range("wind_wave_hs_m", sea.wind_wave_hs_m, 0.0, MAX_HS_M)
    check_range("swell_hs_m", sea.swell_hs_m, 0.0, MAX_HS_M)
    check_range("wind_wave_period_s", sea.wind_wave_period_s, *PERIOD_RANGE_S)
    check_range("swell_period_s", sea.swell_period_s, *PERIOD_RANGE_S)
    check_range("wind speed (wind_u_m_s, wind_v_m_s)", sea.wind_speed_m_s, 0.0, MAX_WIND_M_S)
    check_range(
        "current speed (current_u_m_s, current_v_m_s)",
        np.hypot(sea.current_u_m_s, sea.current_v_m_s), 0.0, MAX_CURRENT_M_S,
    )
    check_range("wind_wave_from_deg", sea.wind_wave_from_deg, -720.0, 720.0)
    check_range("swell_from_deg", sea.swell_from_deg, -720.0, 720.0)
