"""The direct physics model: Holtrop-Mennen + ISO 15016 wind/waves + B-series direct power.

Chain per leg: calm-water resistance (Holtrop-Mennen, at the file's water temperature
and salinity) + wind (ISO 15016, relative wind) + waves (STAWAVE-2, wind sea and swell
separately, head-sea validity handled in ``waves``) -> speed through water from the
thrust balance at the given RPM -> torque, delivered and brake power -> SFOC and fuel ->
SOG/COG with the current -> seakeeping probabilities and IMO flags.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from . import engine as eng
from .currents import over_ground
from .errors import InputRangeError
from .hull import ShipConstants, ship_constants
from .performance import LegPerformance
from .seakeeping import exceedance, imo_flags, motion_m0_unit, stations
from .seastate import SeaState
from .solve import solve_speed
from .spec import ShipSpec
from .spectra import ittc_unit, jonswap_unit
from .validate import check_inputs, check_range, check_sea
from .waves import added_resistance_unit, direction_factor
from .wind import relative_wind, wind_resistance_n


def relative_wave_deg(heading_deg: np.ndarray, from_deg: np.ndarray) -> np.ndarray:
    """Angle between the bow and the direction waves come from (0 = head seas, 0..180)."""
    d = (np.asarray(from_deg) - np.asarray(heading_deg)) % 360.0
    return np.where(d > 180.0, 360.0 - d, d)


class PhysicsModel:
    """Direct (iterative) evaluation of the full physics chain for one ship."""

    def __init__(self, ship: ShipSpec) -> None:
        self.ship = ship
        self.const: ShipConstants = ship_constants(ship)
        self._angles = np.asarray(ship.windage.relative_angle_deg)
        self._caa = np.asarray(ship.windage.caa)
        self._stations = stations(ship)

    # -- resistance pieces -------------------------------------------------------------
    def _wave_spectra(self, heading: np.ndarray, sea: SeaState) -> tuple[np.ndarray, np.ndarray]:
        """Spectra (Hs^2 and validity factor included) of wind sea and swell, (N, n_omega)."""
        f_ws = direction_factor(relative_wave_deg(heading, sea.wind_wave_from_deg))
        f_sw = direction_factor(relative_wave_deg(heading, sea.swell_from_deg))
        s_ws = ittc_unit(sea.wind_wave_period_s) * (sea.wind_wave_hs_m**2 * f_ws)[:, None]
        s_sw = jonswap_unit(sea.swell_period_s) * (sea.swell_hs_m**2 * f_sw)[:, None]
        return s_ws, s_sw

    def added_resistance_n(
        self, stw_m_s: np.ndarray, heading_deg: np.ndarray, sea: SeaState
    ) -> tuple[np.ndarray, np.ndarray]:
        """Wind and wave added resistance (N) at given speeds, 1-D arrays."""
        s_ws, s_sw = self._wave_spectra(heading_deg, sea)
        return self._wind(stw_m_s, heading_deg, sea), self._waves(stw_m_s, s_ws + s_sw)

    def _wind(self, v: np.ndarray, heading: np.ndarray, sea: SeaState) -> np.ndarray:
        spd, ang = relative_wind(v, heading, sea.wind_u_m_s, sea.wind_v_m_s)
        return wind_resistance_n(
            v, spd, ang, self.ship.windage.frontal_area_m2, self._angles, self._caa
        )

    def _waves(self, v: np.ndarray, spectrum: np.ndarray) -> np.ndarray:
        return added_resistance_unit(self.const.wave_hull, v, spectrum, self.const.rho_kg_m3)

    # -- public API --------------------------------------------------------------------
    def evaluate(self, rpm: npt.ArrayLike, heading_deg: npt.ArrayLike,
                 sea: SeaState) -> LegPerformance:
        """Evaluate legs at engine RPM and heading (deg true, going to) in ``sea``."""
        rpm = np.asarray(rpm, dtype=float)
        heading_deg = np.asarray(heading_deg, dtype=float)
        shape = np.broadcast_shapes(rpm.shape, np.shape(heading_deg), sea.shape())
        check_inputs(self.ship, rpm, heading_deg, sea)
        n_legs = int(np.prod(shape))
        rpm1 = np.broadcast_to(rpm, shape).reshape(n_legs)
        hdg = np.broadcast_to(heading_deg, shape).reshape(n_legs)
        s = flatten_sea(sea, shape, n_legs)
        c, p = self.const, self.ship.propeller
        n_rps = rpm1 / 60.0
        s_ws, s_sw = self._wave_spectra(hdg, s)
        spectrum = s_ws + s_sw

        def total(v: np.ndarray, idx: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            r_calm, w = c.calm_resistance_n(v)
            sub = _take(s, idx)
            r = r_calm + self._wind(v, hdg[idx], sub) + self._waves(v, spectrum[idx])
            return r, w

        v = solve_speed(c, n_rps, p.diameter_m, total)
        _, w = c.calm_resistance_n(v)
        j = v * (1.0 - w) / (n_rps * p.diameter_m)
        kq = c.curve.kq(j)
        torque_nm = kq * c.rho_kg_m3 * n_rps**2 * p.diameter_m**5 / c.hm.eta_r
        pb_kw = 2 * np.pi * n_rps * torque_nm / p.shaft_efficiency / 1000.0
        out = self.finish_legs(rpm1, hdg, s, v, pb_kw)
        return LegPerformance(**{k: a.reshape(shape) for k, a in out.items()})

    def finish_legs(
        self, rpm: np.ndarray, hdg: np.ndarray, s: SeaState, v: np.ndarray, pb_kw: np.ndarray
    ) -> dict[str, np.ndarray]:
        """Fuel, limits, currents and seakeeping from speed and brake power (1-D)."""
        e = self.ship.engine
        sog, cog = over_ground(v, hdg, s.current_u_m_s, s.current_v_m_s)
        m0 = self._motion_m0(v, hdg, s)
        thr = self._stations.threshold_m
        flags = self._imo(v, hdg, s)
        return {
            "stw_m_s": v,
            "sog_m_s": sog,
            "cog_deg": cog,
            "brake_power_kw": pb_kw,
            "fuel_t_per_h": eng.fuel_t_per_h(e, pb_kw),
            "engine_load": pb_kw / e.mcr_kw,
            "engine_limit_exceeded": eng.limit_exceeded(e, rpm, pb_kw),
            "p_slamming": exceedance(m0[0], thr[0]),
            "p_deck_wetness": exceedance(m0[1], thr[1]),
            "p_propeller_emergence": exceedance(m0[2], thr[2]),
            "surf_riding": flags[0],
            "parametric_roll": flags[1],
            "synchronous_roll": flags[2],
            "high_wave_group": flags[3],
            "hs_m": s.hs_m,
            "wind_speed_m_s": s.wind_speed_m_s,
        }

    def _motion_m0(self, v: np.ndarray, hdg: np.ndarray, s: SeaState) -> list[np.ndarray]:
        """Relative-motion variance (m^2) at the three stations, wind sea + swell."""
        xs = self._stations.x_m
        rel_ws = relative_wave_deg(hdg, s.wind_wave_from_deg)
        rel_sw = relative_wave_deg(hdg, s.swell_from_deg)
        m_ws = motion_m0_unit(self.ship, v, rel_ws, ittc_unit(s.wind_wave_period_s), xs)
        m_sw = motion_m0_unit(self.ship, v, rel_sw, jonswap_unit(s.swell_period_s), xs)
        return [
            a * s.wind_wave_hs_m**2 + b * s.swell_hs_m**2 for a, b in zip(m_ws, m_sw, strict=True)
        ]

    def _imo(self, v: np.ndarray, hdg: np.ndarray, s: SeaState) -> list[np.ndarray]:
        a = imo_flags(self.ship, v, s.wind_wave_hs_m, s.wind_wave_period_s,
                      relative_wave_deg(hdg, s.wind_wave_from_deg), "ittc")
        b = imo_flags(self.ship, v, s.swell_hs_m, s.swell_period_s,
                      relative_wave_deg(hdg, s.swell_from_deg), "jonswap")
        return [x | y for x, y in zip(a, b, strict=True)]

    def rpm_for_speed(
        self, stw_m_s: np.ndarray, heading_deg: np.ndarray, sea: SeaState
    ) -> np.ndarray:
        """Engine RPM at which the ship makes ``stw_m_s`` through water (inverse of evaluate)."""
        stw = np.asarray(stw_m_s, dtype=float)
        heading_deg = np.asarray(heading_deg, dtype=float)
        shape = np.broadcast_shapes(stw.shape, heading_deg.shape, sea.shape())
        check_range("stw_m_s", stw, 0.05, 30.0)
        check_range("heading_deg", heading_deg, -720.0, 720.0)
        check_sea(sea)
        n_legs = int(np.prod(shape))
        v = np.broadcast_to(stw, shape).reshape(n_legs).copy()
        hdg = np.broadcast_to(heading_deg, shape).reshape(n_legs)
        s = flatten_sea(sea, shape, n_legs)
        c = self.const
        r_calm, w = c.calm_resistance_n(v)
        r_wind, r_wave = self.added_resistance_n(v, hdg, s)
        thrust = (r_calm + r_wind + r_wave) / (1.0 - c.hm.thrust_deduction)
        if np.any(thrust <= 0):
            raise InputRangeError("stw_m_s", "following wind pushes the ship faster than asked")
        return (self._rpm_from_thrust(thrust, v * (1.0 - w)) * 60.0).reshape(shape)

    def _rpm_from_thrust(self, thrust_n: np.ndarray, va_m_s: np.ndarray) -> np.ndarray:
        """Shaft speed (rps) giving ``thrust_n`` at advance speed ``va_m_s``: KT(J)/J^2 = const."""
        c, d = self.const, self.ship.propeller.diameter_m
        target = thrust_n / (c.rho_kg_m3 * d**2 * va_m_s**2)
        lo = np.full(thrust_n.shape, 1e-4)
        hi = np.full(thrust_n.shape, c.j_max)
        for _ in range(60):  # KT/J^2 decreases monotonically on (0, J_max)
            mid = 0.5 * (lo + hi)
            big = c.curve.kt(mid) / mid**2 > target
            lo = np.where(big, mid, lo)
            hi = np.where(big, hi, mid)
        j = 0.5 * (lo + hi)
        return va_m_s / (j * d)


def flatten_sea(sea: SeaState, shape: tuple[int, ...], n: int) -> SeaState:
    b = sea.broadcast(shape)
    return SeaState(**{k: np.ascontiguousarray(a).reshape(n) for k, a in vars(b).items()})


def flatten_legs(
    first: np.ndarray, heading_deg: np.ndarray, sea: SeaState
) -> tuple[tuple[int, ...], int, np.ndarray, np.ndarray, SeaState]:
    """Broadcast (rpm or speed, heading, sea) to one shape and flatten them to n legs."""
    shape = np.broadcast_shapes(first.shape, heading_deg.shape, sea.shape())
    n = int(np.prod(shape))
    return (shape, n, np.broadcast_to(first, shape).reshape(n),
            np.broadcast_to(heading_deg, shape).reshape(n), flatten_sea(sea, shape, n))


def _take(s: SeaState, idx: np.ndarray) -> SeaState:
    return SeaState(**{k: a[idx] for k, a in vars(s).items()})
