"""Wave spectra on a fixed frequency grid: ITTC (Bretschneider) for wind sea, JONSWAP for swell.

Both are parameterised by significant height and mean period T01 (the forecast's
Tm01), as ISO 15016:2015 Annex D prescribes for irregular-wave corrections.
"""

from __future__ import annotations

import numpy as np

OMEGA_RAD_S = np.linspace(0.12, 3.2, 96)  # covers T01 from ~2.5 s to 25 s
D_OMEGA = float(OMEGA_RAD_S[1] - OMEGA_RAD_S[0])
JONSWAP_GAMMA = 3.3
_T1_OVER_TP = 0.834  # JONSWAP, gamma = 3.3


def ittc_unit(period_s: np.ndarray) -> np.ndarray:
    """ITTC two-parameter spectrum per unit Hs^2, shape (..., n_omega), from T01."""
    t1 = np.maximum(np.asarray(period_s, dtype=float), 0.5)[..., None]
    w = OMEGA_RAD_S
    a = 173.0 / t1**4
    b = 691.0 / t1**4
    return a / w**5 * np.exp(-b / w**4)


def jonswap_unit(period_s: np.ndarray) -> np.ndarray:
    """JONSWAP (gamma 3.3) per unit Hs^2, numerically normalised to m0 = 1/16."""
    t1 = np.maximum(np.asarray(period_s, dtype=float), 0.5)[..., None]
    wp = 2 * np.pi * _T1_OVER_TP / t1
    w = OMEGA_RAD_S
    sigma = np.where(w <= wp, 0.07, 0.09)
    pm = w**-5 * np.exp(-1.25 * (wp / w) ** 4)
    s = pm * JONSWAP_GAMMA ** np.exp(-((w - wp) ** 2) / (2 * sigma**2 * wp**2))
    m0 = s.sum(axis=-1, keepdims=True) * D_OMEGA
    return s / (16.0 * np.maximum(m0, 1e-300))
