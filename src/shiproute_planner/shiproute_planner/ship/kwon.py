"""Kwon's (2008) speed-loss method as an alternative ship model (as in the NSGA-II reference).

Kwon, Y.J. (2008), "Speed loss due to added resistance in wind and waves", The Naval
Architect, March: dV/V [%] = C_beta * C_U * C_Form, with the weather-direction
coefficient C_beta(Beaufort number, direction), the speed-reduction coefficient
C_U(Cb, loading, Fn) and the hull-form coefficient C_Form(BN, displacement volume).
The engine is assumed to keep its calm-water output at the given RPM (the method's
premise), so power and fuel are the calm-water values; speed drops by the Kwon loss.
Seakeeping and currents are evaluated as in the physics model at the reduced speed.
"""

from __future__ import annotations

import numpy as np

from .calm import calm_curve
from .performance import LegPerformance
from .physics import PhysicsModel, flatten_legs
from .seastate import SeaState
from .spec import ShipSpec
from .validate import check_inputs, check_range, check_sea

G_M_S2 = 9.80665
# C_U rows: Cb -> (a, b, c) in a + b Fn + c Fn^2 (normal / loaded condition)
_CU_LOADED = {
    0.55: (1.7, -1.4, -7.4), 0.60: (2.2, -2.5, -9.7), 0.65: (2.6, -3.7, -11.6),
    0.70: (3.1, -5.3, -12.4), 0.75: (2.4, -10.6, -9.5), 0.80: (2.6, -13.1, -15.1),
    0.85: (3.1, -18.7, 28.0),
}
_CU_BALLAST = {0.75: (2.6, -12.5, -13.5), 0.80: (3.0, -16.3, -21.6), 0.85: (3.4, -20.9, 31.8)}


def beaufort_number(wind_speed_m_s: np.ndarray) -> np.ndarray:
    """Beaufort number (continuous) from 10 m wind speed: V = 0.836 BN^1.5."""
    return np.clip((np.asarray(wind_speed_m_s) / 0.836) ** (2.0 / 3.0), 0.0, 12.0)


def direction_coefficient(bn: np.ndarray, rel_deg: np.ndarray) -> np.ndarray:
    """C_beta: 1 (head, 0-30 deg), then oblique, beam and following-sea formulas."""
    rel = np.abs(np.asarray(rel_deg))
    return np.select(
        [rel <= 30, rel <= 60, rel <= 150],
        [np.ones_like(bn), (1.7 - 0.03 * (bn - 4) ** 2) / 2, (0.9 - 0.06 * (bn - 6) ** 2) / 2],
        (0.4 - 0.03 * (bn - 8) ** 2) / 2,
    )


def speed_coefficient(cb: float, froude: np.ndarray, ballast: bool) -> np.ndarray:
    """C_U by linear interpolation in Cb between Kwon's tabulated rows."""
    rows = dict(_CU_LOADED)
    if ballast:
        rows.update(_CU_BALLAST)
    cbs = np.array(sorted(rows))
    vals = np.stack([rows[c][0] + rows[c][1] * froude + rows[c][2] * froude**2 for c in cbs])
    cb_c = float(np.clip(cb, cbs[0], cbs[-1]))
    i = min(int(np.searchsorted(cbs, cb_c, side="right")) - 1, len(cbs) - 2)
    f = (cb_c - cbs[i]) / (cbs[i + 1] - cbs[i])
    return vals[i] * (1 - f) + vals[i + 1] * f


def form_coefficient(bn: np.ndarray, volume_m3: float, ship_type: str, ballast: bool) -> np.ndarray:
    """C_Form: container ships (normal loading), other ships laden or in ballast."""
    v23 = volume_m3 ** (2.0 / 3.0)
    if ship_type == "container":
        return 0.7 * bn + bn**6.5 / (22.0 * v23)
    if ballast:
        return 0.7 * bn + bn**6.5 / (2.7 * v23)
    return 0.5 * bn + bn**6.5 / (2.7 * v23)


class KwonModel:
    """Calm-water RPM curve from the physics model, speed reduced by Kwon's loss."""

    def __init__(self, ship: ShipSpec) -> None:
        self.ship = ship
        self.physics = PhysicsModel(ship)
        self.curve = calm_curve(self.physics)
        self._ballast = "ballast" in ship.condition.name.lower()
        c = self.physics.const
        self._volume_m3 = ship.condition.displacement_t * 1000.0 / c.rho_kg_m3
        self._cb = c.hm.cb

    def speed_loss_fraction(
        self, calm_speed_m_s: np.ndarray, heading_deg: np.ndarray, sea: SeaState
    ) -> np.ndarray:
        """Kwon's dV/V (fraction, 0..0.99) for calm-water speed, heading and weather."""
        bn = beaufort_number(sea.wind_speed_m_s)
        wind_from = np.degrees(np.arctan2(-sea.wind_u_m_s, -sea.wind_v_m_s))
        rel = np.abs((wind_from - heading_deg + 180.0) % 360.0 - 180.0)
        fn = calm_speed_m_s / np.sqrt(G_M_S2 * self.ship.hull.lwl_m)
        loss_pct = (
            direction_coefficient(bn, rel)
            * speed_coefficient(self._cb, fn, self._ballast)
            * form_coefficient(bn, self._volume_m3, self.ship.ship_type, self._ballast)
        )
        return np.clip(loss_pct / 100.0, 0.0, 0.99)

    def evaluate(self, rpm: np.ndarray, heading_deg: np.ndarray, sea: SeaState) -> LegPerformance:
        """Evaluate legs (same contract as ``PhysicsModel.evaluate``)."""
        rpm = np.asarray(rpm, dtype=float)
        heading_deg = np.asarray(heading_deg, dtype=float)
        check_inputs(self.ship, rpm, heading_deg, sea)
        shape, _, rpm1, hdg, s = flatten_legs(rpm, heading_deg, sea)
        v_calm, pb, _ = self.curve.at_rpm(rpm1)
        v = v_calm * (1.0 - self.speed_loss_fraction(v_calm, hdg, s))
        out = self.physics.finish_legs(rpm1, hdg, s, v, pb)
        return LegPerformance(**{k: a.reshape(shape) for k, a in out.items()})

    def rpm_for_speed(
        self, stw_m_s: np.ndarray, heading_deg: np.ndarray, sea: SeaState
    ) -> np.ndarray:
        """RPM whose Kwon-reduced speed equals ``stw_m_s`` (fixed-point on the calm speed)."""
        stw = np.asarray(stw_m_s, dtype=float)
        check_range("stw_m_s", stw, 0.05, 30.0)
        check_sea(sea)
        v_calm = np.array(stw, copy=True)
        for _ in range(30):
            v_calm = stw / (1.0 - self.speed_loss_fraction(v_calm, heading_deg, sea))
        return self.curve.rpm_at_speed(v_calm)


