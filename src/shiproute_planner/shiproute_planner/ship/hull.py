"""Per-ship derived constants shared by the physics and tabulated models."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .holtrop_mennen import HMCoefficients, HMHull, coefficients, resistance
from .propeller import OpenWaterCurve, open_water_curve
from .spec import ShipSpec
from .water import density_kg_m3, kinematic_viscosity_m2_s
from .waves import WaveHull


@dataclass(frozen=True)
class ShipConstants:
    """Water properties, Holtrop-Mennen inputs, propeller curve and STAWAVE-2 hull."""

    rho_kg_m3: float
    nu_m2_s: float
    hm_hull: HMHull
    hm: HMCoefficients
    curve: OpenWaterCurve
    j_max: float  # advance ratio of zero thrust
    wave_hull: WaveHull
    max_wake_fraction: float  # largest wake fraction over 0.5..25 m/s (speed brackets)

    def calm_resistance_n(self, speed_m_s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Calm-water total resistance (N) and wake fraction at ``speed_m_s``."""
        r = resistance(self.hm_hull, self.hm, speed_m_s, self.rho_kg_m3, self.nu_m2_s)
        return r.r_total_n, r.wake_fraction


def ship_constants(ship: ShipSpec) -> ShipConstants:
    """Derive the constants of ``ship`` in its loading condition."""
    rho = density_kg_m3(ship.water.temperature_c, ship.water.salinity_psu)
    nu = kinematic_viscosity_m2_s(ship.water.temperature_c, ship.water.salinity_psu)
    h, p, c = ship.hull, ship.propeller, ship.condition
    volume = c.displacement_t * 1000.0 / rho
    hm_hull = HMHull(
        lwl_m=h.lwl_m, breadth_m=h.breadth_m, draft_fore_m=c.draft_fore_m,
        draft_aft_m=c.draft_aft_m, volume_m3=volume, midship_coefficient=h.midship_coefficient,
        waterplane_coefficient=h.waterplane_coefficient, lcb_percent=h.lcb_percent,
        bulb_area_m2=h.bulb_area_m2 if c.bulb_area_m2 is None else c.bulb_area_m2,
        bulb_center_height_m=(
            h.bulb_center_height_m if c.bulb_center_height_m is None else c.bulb_center_height_m
        ),
        transom_area_m2=h.transom_area_m2, appendage_area_m2=h.appendage_area_m2,
        appendage_form_factor=h.appendage_form_factor,
        stern_shape_coefficient=h.stern_shape_coefficient, wetted_surface_m2=h.wetted_surface_m2,
        propeller_diameter_m=p.diameter_m, propeller_area_ratio=p.area_ratio,
    )
    hm = coefficients(hm_hull)
    curve = open_water_curve(p.pitch_ratio, p.area_ratio, p.blades)
    j_max = curve.j_zero_thrust()
    w_max = float(np.max(resistance(hm_hull, hm, np.linspace(0.5, 25, 50), rho, nu).wake_fraction))
    wave_hull = WaveHull(
        lpp_m=h.lpp_m, breadth_m=h.breadth_m, mean_draft_m=ship.mean_draft_m,
        cb=volume / (h.lpp_m * h.breadth_m * ship.mean_draft_m), kyy=h.pitch_gyradius_ratio,
    )
    return ShipConstants(rho, nu, hm_hull, hm, curve, j_max, wave_hull, min(w_max, 0.7))
