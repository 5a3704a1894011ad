"""Sea-water density and kinematic viscosity from temperature and salinity.

Density: UNESCO EOS-80 one-atmosphere equation (Millero & Poisson 1981). Viscosity:
ITTC 7.5-02-01-03 (2011) fit for sea water. Using the actual water in the resistance
and propeller terms is the ISO 15016 temperature/density correction.
"""

from __future__ import annotations


def density_kg_m3(temperature_c: float, salinity_psu: float) -> float:
    """Sea-water density at the surface (kg/m^3)."""
    t, s = temperature_c, salinity_psu
    rho_w = (
        999.842594 + 6.793952e-2 * t - 9.095290e-3 * t**2 + 1.001685e-4 * t**3
        - 1.120083e-6 * t**4 + 6.536332e-9 * t**5
    )
    a = 0.824493 - 4.0899e-3 * t + 7.6438e-5 * t**2 - 8.2467e-7 * t**3 + 5.3875e-9 * t**4
    b = -5.72466e-3 + 1.0227e-4 * t - 1.6546e-6 * t**2
    return rho_w + a * s + b * s**1.5 + 4.8314e-4 * s**2


def kinematic_viscosity_m2_s(temperature_c: float, salinity_psu: float) -> float:
    """Kinematic viscosity (m^2/s); salinity scales between fresh (ITTC) and 35 psu sea water."""
    t = temperature_c
    sea = (0.659e-3 * (t - 1.0) ** 2 - 0.05076 * (t - 1.0) + 1.7688) * 1e-6
    fresh = (0.585e-3 * (t - 12.0) ** 2 - 0.03361 * (t - 12.0) + 1.2350) * 1e-6
    return fresh + (sea - fresh) * min(max(salinity_psu, 0.0), 42.0) / 35.0
