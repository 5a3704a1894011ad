"""Mean added resistance in irregular waves by STAWAVE-2 (ISO 15016:2015, Annex D).

R_AW = 2 * integral (R_AW(omega) / zeta_A^2) S(omega) d omega, with the regular-wave
transfer function R_AW = R_AWML (motion, empirical) + R_AWRL (reflection) of Boom,
Huisman & Mennen (2013) as adopted in ISO 15016:2015 and ITTC 7.5-04-01-01.1 (2014).
STAWAVE-2 is valid for head waves within +-45 deg off the bow. Outside that range we
follow the trial-analysis practice of not extrapolating: the result is tapered with a
raised cosine from full at 45 deg to zero at 90 deg and is zero for beam and following
seas (a documented choice; following-sea thrust gains are ignored).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.special import i1e, k1e

from .spectra import D_OMEGA, OMEGA_RAD_S

G_M_S2 = 9.80665
HEAD_SEA_LIMIT_DEG = 45.0
BEAM_SEA_DEG = 90.0


@dataclass(frozen=True)
class WaveHull:
    """Hull data STAWAVE-2 needs."""

    lpp_m: float
    breadth_m: float
    mean_draft_m: float
    cb: float
    kyy: float  # pitch radius of gyration / Lpp


def direction_factor(rel_wave_deg: np.ndarray) -> np.ndarray:
    """Validity factor: 1 within +-45 deg of head seas, cosine taper to 0 at beam seas."""
    b = np.abs(np.asarray(rel_wave_deg, dtype=float))
    x = np.clip((b - HEAD_SEA_LIMIT_DEG) / (BEAM_SEA_DEG - HEAD_SEA_LIMIT_DEG), 0.0, 1.0)
    return 0.5 * (1.0 + np.cos(np.pi * x))


def reflection_alpha(h: WaveHull) -> np.ndarray:
    """alpha_T(omega) = pi^2 I1^2 / (pi^2 I1^2 + K1^2) at 1.5 k T on ``OMEGA_RAD_S``."""
    x = 1.5 * OMEGA_RAD_S**2 / G_M_S2 * h.mean_draft_m
    ratio = k1e(x) / i1e(x) * np.exp(-2.0 * x) / np.pi  # K1 / (pi I1)
    return 1.0 / (1.0 + ratio**2)


def transfer_per_zeta2(h: WaveHull, speed_m_s: np.ndarray, rho_kg_m3: float) -> np.ndarray:
    """Regular-wave R_AW / zeta_A^2 (N/m^2), shape (..., n_omega), in head waves.

    R_AWML = 4 rho g B^2/L r_aw(omega_bar), r_aw = omega_bar^b1 exp(b1/d1 (1 - omega_bar^d1))
    a1 Fr^1.5 exp(-3.5 Fr), a1 = 60.3 Cb^1.34, b1 = 11 / -8.5 and d1 = 14 / -566 (L/B)^-2.66
    below / above omega_bar = 1; R_AWRL = 1/2 rho g B alpha_T f1 with
    f1 = 0.692 (V / sqrt(T g))^0.769 + 1.81 Cb^6.95.
    """
    v = np.maximum(np.asarray(speed_m_s, dtype=float), 0.0)[..., None]
    fr = np.maximum(v / np.sqrt(G_M_S2 * h.lpp_m), 1e-4)
    # omega_bar = sqrt(L/g) k_yy^(1/3) / (1.17 Fr^-0.143) omega
    w_bar = (np.sqrt(h.lpp_m / G_M_S2) * h.kyy ** (1 / 3) / 1.17) * fr**0.143 * OMEGA_RAD_S
    low = w_bar < 1.0
    b1 = np.where(low, 11.0, -8.5)
    d1 = np.where(low, 14.0, -566.0 * (h.lpp_m / h.breadth_m) ** -2.66)
    a1 = 60.3 * h.cb**1.34
    r_bar = w_bar**b1 * np.exp(b1 / d1 * (1.0 - w_bar**d1)) * a1 * fr**1.5 * np.exp(-3.5 * fr)
    r_motion = 4.0 * rho_kg_m3 * G_M_S2 * h.breadth_m**2 / h.lpp_m * r_bar
    f1 = 0.692 * (v / np.sqrt(h.mean_draft_m * G_M_S2)) ** 0.769 + 1.81 * h.cb**6.95
    r_refl = 0.5 * rho_kg_m3 * G_M_S2 * h.breadth_m * reflection_alpha(h) * f1
    return r_motion + r_refl


def added_resistance_unit(
    h: WaveHull, speed_m_s: np.ndarray, spectrum_unit: np.ndarray, rho_kg_m3: float
) -> np.ndarray:
    """Head-sea R_AW per unit Hs^2 (N/m^2) for spectra normalised per unit Hs^2."""
    tf = transfer_per_zeta2(h, speed_m_s, rho_kg_m3)
    return 2.0 * np.sum(tf * spectrum_unit, axis=-1) * D_OMEGA
