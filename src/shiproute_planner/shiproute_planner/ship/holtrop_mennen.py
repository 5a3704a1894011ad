"""Calm-water resistance and hull-propeller interaction by Holtrop & Mennen.

Holtrop, J. & Mennen, G.G.J. (1982), "An approximate power prediction method",
International Shipbuilding Progress 29(335); half angle of entrance from Holtrop (1984),
"A statistical re-analysis of resistance and propulsion data", ISP 31(363). Wave
resistance uses the 1982 formulation (valid for Froude numbers up to about 0.45),
which is the one of the published worked example the tests reproduce.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

G_M_S2 = 9.80665


@dataclass(frozen=True)
class HMHull:
    """Inputs of the Holtrop-Mennen method (length is the waterline length)."""

    lwl_m: float
    breadth_m: float
    draft_fore_m: float
    draft_aft_m: float
    volume_m3: float
    midship_coefficient: float
    waterplane_coefficient: float
    lcb_percent: float
    bulb_area_m2: float
    bulb_center_height_m: float
    transom_area_m2: float
    appendage_area_m2: float
    appendage_form_factor: float
    stern_shape_coefficient: float
    wetted_surface_m2: float | None
    propeller_diameter_m: float
    propeller_area_ratio: float


@dataclass(frozen=True)
class HMCoefficients:
    """Speed-independent coefficients derived from the hull."""

    cb: float
    cp: float
    lr_m: float
    form_factor: float  # 1 + k1
    wetted_surface_m2: float
    c1: float
    c2: float
    c5: float
    m1: float
    c15: float
    lam: float
    half_entrance_angle_deg: float
    eta_r: float
    thrust_deduction: float


@dataclass(frozen=True)
class HMResult:
    """Resistance components (N) and propulsion factors at the given speeds (arrays)."""

    froude: np.ndarray
    cf: np.ndarray
    r_friction_n: np.ndarray  # ITTC-57 flat plate, without form factor
    r_appendage_n: np.ndarray
    r_wave_n: np.ndarray
    r_bulb_n: np.ndarray
    r_transom_n: np.ndarray
    r_correlation_n: np.ndarray
    r_total_n: np.ndarray
    wake_fraction: np.ndarray
    thrust_deduction: float
    eta_r: float


def coefficients(h: HMHull) -> HMCoefficients:
    """Compute the speed-independent Holtrop-Mennen coefficients of a hull."""
    L, B = h.lwl_m, h.breadth_m
    T = 0.5 * (h.draft_fore_m + h.draft_aft_m)
    cb = h.volume_m3 / (L * B * T)
    cp = cb / h.midship_coefficient
    lcb = h.lcb_percent
    lr = L * (1.0 - cp + 0.06 * cp * lcb / (4.0 * cp - 1.0))
    tl = T / L
    if tl > 0.05:
        c12 = tl**0.2228446
    elif tl > 0.02:
        c12 = 48.20 * (tl - 0.02) ** 2.078 + 0.479948
    else:
        c12 = 0.479948
    c13 = 1.0 + 0.003 * h.stern_shape_coefficient
    k1 = c13 * (
        0.93
        + c12 * (B / lr) ** 0.92497 * (0.95 - cp) ** -0.521448 * (1.0 - cp + 0.0225 * lcb) ** 0.6906
    )
    abt = h.bulb_area_m2
    if h.wetted_surface_m2 is not None:
        s = h.wetted_surface_m2
    else:
        s = L * (2 * T + B) * np.sqrt(h.midship_coefficient) * (
            0.4530 + 0.4425 * cb - 0.2862 * h.midship_coefficient - 0.003467 * B / T
            + 0.3696 * h.waterplane_coefficient
        ) + 2.38 * abt / cb
    bl = B / L
    if bl < 0.11:
        c7 = 0.229577 * bl**0.33333
    elif bl < 0.25:
        c7 = bl
    else:
        c7 = 0.5 - 0.0625 / bl
    ie = 1.0 + 89.0 * np.exp(
        -((L / B) ** 0.80856)
        * (1.0 - h.waterplane_coefficient) ** 0.30484
        * (1.0 - cp - 0.0225 * lcb) ** 0.6367
        * (lr / B) ** 0.34574
        * (100.0 * h.volume_m3 / L**3) ** 0.16302
    )
    c1 = 2223105.0 * c7**3.78613 * (T / B) ** 1.07961 * (90.0 - ie) ** -1.37565
    c3 = 0.56 * abt**1.5 / (B * T * (0.31 * np.sqrt(abt) + h.draft_fore_m - h.bulb_center_height_m))
    c2 = float(np.exp(-1.89 * np.sqrt(c3)))
    c5 = 1.0 - 0.8 * h.transom_area_m2 / (B * T * h.midship_coefficient)
    lam = 1.446 * cp - 0.03 * L / B if L / B < 12 else 1.446 * cp - 0.36
    c16 = 8.07981 * cp - 13.8673 * cp**2 + 6.984388 * cp**3 if cp < 0.8 else 1.73014 - 0.7067 * cp
    m1 = 0.0140407 * L / T - 1.75254 * h.volume_m3 ** (1 / 3) / L - 4.79323 * B / L - c16
    slender = L**3 / h.volume_m3
    if slender < 512:
        c15 = -1.69385
    elif slender < 1727:
        c15 = -1.69385 + (L / h.volume_m3 ** (1 / 3) - 8.0) / 2.36
    else:
        c15 = 0.0
    eta_r = 0.9922 - 0.05908 * h.propeller_area_ratio + 0.07424 * (cp - 0.0225 * lcb)
    d = h.propeller_diameter_m
    t = (
        0.25014 * bl**0.28956 * (np.sqrt(B * T) / d) ** 0.2624
        / (1.0 - cp + 0.0225 * lcb) ** 0.01762
        + 0.0015 * h.stern_shape_coefficient
    )
    return HMCoefficients(
        cb=cb, cp=cp, lr_m=lr, form_factor=k1, wetted_surface_m2=float(s), c1=c1, c2=c2, c5=c5,
        m1=m1, c15=c15, lam=lam, half_entrance_angle_deg=float(ie), eta_r=eta_r,
        thrust_deduction=float(t),
    )


def resistance(
    h: HMHull, c: HMCoefficients, speed_m_s: np.ndarray, rho_kg_m3: float, nu_m2_s: float
) -> HMResult:
    """Calm-water resistance components and wake fraction at the speeds ``speed_m_s``."""
    v = np.maximum(np.asarray(speed_m_s, dtype=float), 1e-3)
    L, B = h.lwl_m, h.breadth_m
    q = 0.5 * rho_kg_m3 * v**2
    fn = v / np.sqrt(G_M_S2 * L)
    rn = v * L / nu_m2_s
    cf = 0.075 / (np.log10(rn) - 2.0) ** 2
    s = c.wetted_surface_m2
    rf = q * s * cf
    rapp = q * h.appendage_area_m2 * h.appendage_form_factor * cf
    m2 = c.c15 * c.cp**2 * np.exp(-0.1 / fn**2)
    rw = (
        c.c1 * c.c2 * c.c5 * h.volume_m3 * rho_kg_m3 * G_M_S2
        * np.exp(c.m1 * fn**-0.9 + m2 * np.cos(c.lam / fn**2))
    )
    abt, hb, tf = h.bulb_area_m2, h.bulb_center_height_m, h.draft_fore_m
    if abt > 0:
        # near-surface bulbs (ballast drafts) are clamped to the formula's defined range
        pb = 0.56 * np.sqrt(abt) / max(tf - 1.5 * hb, 0.1)
        immersion = max(tf - hb - 0.25 * np.sqrt(abt), 0.1)
        fni = v / np.sqrt(G_M_S2 * immersion + 0.15 * v**2)
        rb = 0.11 * np.exp(-3.0 / pb**2) * fni**3 * abt**1.5 * rho_kg_m3 * G_M_S2 / (1 + fni**2)
    else:
        rb = np.zeros_like(v)
    at = h.transom_area_m2
    if at > 0:
        fnt = v / np.sqrt(2 * G_M_S2 * at / (B + B * h.waterplane_coefficient))
        c6 = np.where(fnt < 5, 0.2 * (1 - 0.2 * fnt), 0.0)
        rtr = q * at * c6
    else:
        rtr = np.zeros_like(v)
    c4 = min(tf / L, 0.04)
    ca = (
        0.006 * (L + 100) ** -0.16 - 0.00205
        + 0.003 * np.sqrt(L / 7.5) * c.cb**4 * c.c2 * (0.04 - c4)
    )
    ra = q * s * ca
    total = rf * c.form_factor + rapp + rw + rb + rtr + ra
    wake = _wake_fraction(h, c, cf * c.form_factor + ca)
    return HMResult(
        froude=fn, cf=cf, r_friction_n=rf, r_appendage_n=rapp, r_wave_n=rw, r_bulb_n=rb,
        r_transom_n=rtr, r_correlation_n=ra, r_total_n=total, wake_fraction=wake,
        thrust_deduction=c.thrust_deduction, eta_r=c.eta_r,
    )


def _wake_fraction(h: HMHull, c: HMCoefficients, cv: np.ndarray) -> np.ndarray:
    """Single-screw effective wake fraction (Holtrop & Mennen 1982)."""
    L, B, ta, d = h.lwl_m, h.breadth_m, h.draft_aft_m, h.propeller_diameter_m
    s = c.wetted_surface_m2
    narrow = B / ta < 5
    c8 = B * s / (L * d * ta) if narrow else s * (7 * B / ta - 25) / (L * d * (B / ta - 3))
    c9 = c8 if c8 < 28 else 32 - 16 / (c8 - 24)
    c11 = ta / d if ta / d < 2 else 0.0833333 * (ta / d) ** 3 + 1.33333
    cp1 = 1.45 * c.cp - 0.315 - 0.0225 * h.lcb_percent
    cs = h.stern_shape_coefficient
    return (
        c9 * cv * L / ta * (0.0661875 + 1.21756 * c11 * cv / (1 - cp1))
        + 0.24558 * np.sqrt(B / (L * (1 - cp1)))
        - 0.09726 / (0.95 - c.cp)
        + 0.11434 / (0.95 - c.cb)
        + 0.75 * cs * cv
        + 0.002 * cs
    )
