"""Wind-sea growth (fetch/duration limited) and the JONSWAP mean/peak period ratio.

Growth laws (U = 10 m wind speed, chi = g F / U^2 dimensionless fetch):
  JONSWAP, Hasselmann et al. (1973), Dtsch. Hydrogr. Z. A8(12):
    g Hs / U^2 = 1.6e-3 chi^(1/2)            (from dimensionless energy 1.6e-7 chi)
    g Tp / U   = 0.286 chi^(1/3)             (from nu = f_p U / g = 3.5 chi^(-0.33))
  Duration-fetch equivalence, Shore Protection Manual (CERC 1984):
    g t / U = 68.8 chi^(2/3)
  Fully developed cap, Pierson & Moskowitz (1964): dimensionless energy 3.64e-3, i.e.
    g Hs / U^2 = 0.241, reached at chi = 22,750.
Changing winds use the SPM "equivalent duration" method: the present wind sea is converted to
the duration that the new wind needs to raise it, the time step is added, and the result is
capped by the fetch-limited and fully developed values.
"""

from __future__ import annotations

import numpy as np

from .spectral import period_over_tp

G = 9.81
CHI_FULLY_DEVELOPED = (0.241 / 1.6e-3) ** 2


def jonswap_tm01_over_tp(gamma: float) -> float:
    """Tm01 / Tp of a JONSWAP spectrum with peak enhancement gamma."""
    return period_over_tp("tm01", gamma)


def duration_to_chi(t_s: np.ndarray, u_m_s: np.ndarray) -> np.ndarray:
    """Dimensionless fetch equivalent to a duration t under wind U (SPM 1984)."""
    return (G * t_s / u_m_s / 68.8) ** 1.5


def chi_to_duration_s(chi: np.ndarray, u_m_s: np.ndarray) -> np.ndarray:
    """Duration under wind U equivalent to dimensionless fetch chi (SPM 1984)."""
    return 68.8 * chi ** (2.0 / 3.0) * u_m_s / G


def hs_from_chi(chi: np.ndarray, u_m_s: np.ndarray) -> np.ndarray:
    """Significant wave height (m) of a fetch-limited JONSWAP sea."""
    return 1.6e-3 * np.sqrt(chi) * u_m_s ** 2 / G


def tp_from_chi(chi: np.ndarray, u_m_s: np.ndarray) -> np.ndarray:
    """Peak period (s) of a fetch-limited JONSWAP sea."""
    return 0.286 * np.cbrt(chi) * u_m_s / G


def chi_from_hs(hs_m: np.ndarray, u_m_s: np.ndarray) -> np.ndarray:
    """Inverse of hs_from_chi."""
    return (hs_m * G / (1.6e-3 * u_m_s ** 2)) ** 2


def grow_step(hs_m: np.ndarray, dir_from_deg: np.ndarray, u_m_s: np.ndarray,
              wind_from_deg: np.ndarray, fetch_m: np.ndarray,
              dt_s: float) -> tuple[np.ndarray, np.ndarray]:
    """Advance the wind sea by dt_s under a new wind; returns (hs_m, tp_s).

    Energy carried over is scaled by max(cos(turn), 0)^2 when the wind turns (the turned-away
    part leaves the wind sea as swell), then the equivalent-duration method is applied.
    """
    u = np.maximum(u_m_s, 0.5)
    turn = np.deg2rad(wind_from_deg - dir_from_deg)
    carried = hs_m * np.maximum(np.cos(turn), 0.0)
    chi_cap = np.minimum(G * fetch_m / u ** 2, CHI_FULLY_DEVELOPED)
    chi_old = np.minimum(chi_from_hs(carried, u), chi_cap)
    chi = np.minimum(duration_to_chi(chi_to_duration_s(chi_old, u) + dt_s, u), chi_cap)
    return hs_from_chi(chi, u), tp_from_chi(chi, u)
