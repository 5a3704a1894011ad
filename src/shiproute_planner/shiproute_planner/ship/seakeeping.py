"""Seakeeping per leg: relative-motion exceedance probabilities and IMO MSC.1/Circ.1228 flags.

Heave and pitch follow the closed-form frequency responses of a homogeneously loaded
box-shaped hull (Jensen, Mansour & Olsen 2004, Ocean Eng. 31; the simplified model the
ABS guidance notes use), with the box breadth B*Cb. The relative vertical motion at a
station is heave + pitch lever - incident wave; its spectral variance m0 gives the
Rayleigh probability that an amplitude exceeds A: P = exp(-A^2 / (2 m0)), with A the
forward draft (slamming, 0.1 L aft of FP), the bow freeboard (deck wetness, FP) and the
propeller-tip immersion (propeller emergence, AP).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from shiproute_core.units import M_S_PER_KNOT

from .spec import ShipSpec
from .spectra import D_OMEGA, OMEGA_RAD_S

G_M_S2 = 9.80665
_PEAK_OVER_MEAN = {"ittc": 1.0 / 0.772, "jonswap": 1.0 / 0.834}


@dataclass(frozen=True)
class Stations:
    """Positions (m forward of midship) and exceedance thresholds (m) of the three events."""

    x_m: tuple[float, float, float]  # slamming, deck wetness, propeller emergence
    threshold_m: tuple[float, float, float]


def stations(ship: ShipSpec) -> Stations:
    """Stations and thresholds of a ship in its loading condition."""
    L = ship.hull.lpp_m
    tf, ta = ship.condition.draft_fore_m, ship.condition.draft_aft_m
    x_slam = 0.4 * L
    draft_slam = 0.5 * (tf + ta) + (tf - ta) * x_slam / L
    freeboard = ship.hull.bow_height_m - tf
    tip = ta - ship.propeller.shaft_center_height_m - 0.5 * ship.propeller.diameter_m
    return Stations((x_slam, 0.5 * L, -0.5 * L), (draft_slam, freeboard, tip))


def _heave_pitch(
    ship: ShipSpec, speed_m_s: np.ndarray, rel_wave_deg: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Complex-free pieces of the box-hull response: heave, pitch (per wave amplitude), k_e."""
    L = ship.hull.lpp_m
    T = ship.mean_draft_m
    cb = ship.condition.displacement_t / 1.025 / (ship.hull.lwl_m * ship.hull.breadth_m * T)
    b = ship.hull.breadth_m * cb
    w = OMEGA_RAD_S
    v = np.asarray(speed_m_s, dtype=float)[..., None]
    cos_mu = np.cos(np.radians(np.asarray(rel_wave_deg, dtype=float)))[..., None]
    k = w**2 / G_M_S2
    ke = k * cos_mu  # signed: positive when the wave meets the bow first
    alpha = 1.0 + w * v * cos_mu / G_M_S2  # encounter / wave frequency
    alpha = np.where(np.abs(alpha) < 0.2, np.copysign(0.2, alpha), alpha)
    a = 2.0 * np.sin(0.5 * k * b * alpha**2) * np.exp(-k * T * alpha**2)
    f = np.sqrt((1.0 - k * T) ** 2 + (a**2 / (k * b * np.abs(alpha) ** 3)) ** 2)
    kappa_f = np.exp(-np.abs(ke) * T) * f
    y = 0.5 * ke * L
    small = np.abs(y) < 1e-3
    ys = np.where(small, 1.0, y)
    g_ratio = np.where(small, 2.0 * y / 3.0, (np.sin(ys) - ys * np.cos(ys)) / ys**2)
    eta = 1.0 / np.sqrt((1.0 - 2.0 * k * T * alpha**2) ** 2 + (a**2 / (k * b * alpha**2)) ** 2)
    heave = eta * kappa_f * np.sinc(y / np.pi)
    pitch = eta * kappa_f * 3.0 * g_ratio / (0.5 * L)  # = kappa f ke in long waves
    return heave, pitch, ke


def relative_motion_rao2(
    ship: ShipSpec, speed_m_s: np.ndarray, rel_wave_deg: np.ndarray, x_m: float
) -> np.ndarray:
    """|relative motion / wave amplitude|^2 at station ``x_m``, shape (..., n_omega).

    ``rel_wave_deg``: direction the waves come from relative to the bow (0 = head seas).
    """
    heave, pitch, ke = _heave_pitch(ship, speed_m_s, rel_wave_deg)
    return _station_rao2(heave, pitch, ke, x_m)


def _station_rao2(heave: np.ndarray, pitch: np.ndarray, ke: np.ndarray, x_m: float) -> np.ndarray:
    re = heave - np.cos(ke * x_m)
    im = x_m * pitch - np.sin(ke * x_m)
    return re**2 + im**2


def motion_m0_unit(
    ship: ShipSpec, speed_m_s: np.ndarray, rel_wave_deg: np.ndarray, spectrum_unit: np.ndarray,
    xs_m: tuple[float, ...],
) -> list[np.ndarray]:
    """Variance of the relative motion per unit Hs^2 at each station in ``xs_m``."""
    heave, pitch, ke = _heave_pitch(ship, speed_m_s, rel_wave_deg)
    return [
        np.sum(_station_rao2(heave, pitch, ke, x) * spectrum_unit, axis=-1) * D_OMEGA
        for x in xs_m
    ]


def exceedance(m0_m2: np.ndarray, threshold_m: float) -> np.ndarray:
    """Rayleigh probability that a relative-motion amplitude exceeds ``threshold_m``."""
    if threshold_m <= 0:
        return np.ones_like(m0_m2)
    return np.exp(-(threshold_m**2) / (2.0 * np.maximum(m0_m2, 1e-12)))


def natural_roll_period_s(ship: ShipSpec) -> float:
    """Roll period from the file, else the IMO IS Code (2008) estimate 2 C B / sqrt(GM)."""
    if ship.condition.roll_period_s is not None:
        return ship.condition.roll_period_s
    b, d = ship.hull.breadth_m, ship.mean_draft_m
    c = 0.373 + 0.023 * b / d - 0.043 * ship.hull.lwl_m / 100.0
    return 2.0 * c * b / np.sqrt(ship.condition.gm_m)


def imo_flags(
    ship: ShipSpec,
    stw_m_s: np.ndarray,
    hs_m: np.ndarray,
    mean_period_s: np.ndarray,
    rel_wave_deg: np.ndarray,
    spectrum: str,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """MSC.1/Circ.1228 flags for one wave system: surf-riding, parametric, synchronous, high waves.

    ``rel_wave_deg`` 0 = head seas, 180 = following; the peak period sets wave length
    and encounter period.
    """
    L = ship.hull.lpp_m
    tp = mean_period_s * _PEAK_OVER_MEAN[spectrum]
    wave_len = G_M_S2 * tp**2 / (2 * np.pi)
    present = hs_m >= ship.seakeeping.min_hs_imo_check_m
    rel = np.abs(((rel_wave_deg + 180.0) % 360.0) - 180.0)
    following = rel > 135.0
    cos_from_stern = np.cos(np.radians(180.0 - rel))
    v_kn = stw_m_s / M_S_PER_KNOT
    surf = present & following & (v_kn * np.maximum(cos_from_stern, 1e-6) > 1.8 * np.sqrt(L))
    high = present & (wave_len > 0.8 * L) & (hs_m > 0.04 * L)
    wp = 2 * np.pi / tp
    we = np.abs(wp + wp**2 * stw_m_s * np.cos(np.radians(rel)) / G_M_S2)
    te = 2 * np.pi / np.maximum(we, 1e-6)
    tr = natural_roll_period_s(ship)
    tol = ship.seakeeping.roll_resonance_tolerance
    sync = present & (np.abs(te / tr - 1.0) < tol)
    # parametric roll needs the waves to run along the hull (the waterplane changes with the
    # wave passage): head or following seas within 45 deg, as in the ABS parametric roll guide
    along = (rel <= 45.0) | (rel >= 135.0)
    param = present & along & (np.abs(te / (0.5 * tr) - 1.0) < tol)
    return surf, param, sync, high
