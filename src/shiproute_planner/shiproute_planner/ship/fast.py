"""Tabulated fast model: the physics chain with speed-dependent integrals precomputed.

Tables per ship and loading condition (built in about a second from the physics model):
calm-water resistance and wake fraction vs speed, STAWAVE-2 added resistance per unit
Hs^2 vs (speed, mean period) for the wind-sea and swell spectra, and relative-motion
variance per unit Hs^2 vs (speed, period, relative wave angle) at the three seakeeping
stations. A numba kernel then solves the thrust balance per leg. Agreement with
``PhysicsModel`` is tested (< 0.5 % in speed, power and fuel).
"""

from __future__ import annotations

import os
import threading
from concurrent.futures import ThreadPoolExecutor
from itertools import pairwise

import numpy as np

from ..threads import planner_threads
from . import fast_kernel as fk
from .errors import InputRangeError, ShipModelError
from .fast_inverse import rpm_kernel
from .hull import ShipConstants
from .leg_inputs import KernelTables, LegInputs, leg_inputs
from .performance import LegPerformance
from .physics import PhysicsModel
from .seakeeping import natural_roll_period_s, relative_motion_rao2
from .seastate import SeaState
from .spec import ShipSpec
from .spectra import D_OMEGA, ittc_unit, jonswap_unit
from .validate import (
    MAX_CURRENT_M_S,
    MAX_HS_M,
    MAX_WIND_M_S,
    PERIOD_RANGE_S,
    check_range,
    check_sea,
)
from .waves import added_resistance_unit

_PERIOD_GRID_S = np.linspace(0.5, 30.0, 119)
_COS_GRID = np.linspace(-1.0, 1.0, 81)  # cos(relative wave angle), following .. head
_N_CALM = 2048
_N_WAVE_V = 97
_N_MOTION_V = 25


class FastModel:
    """``PerformanceModel`` backed by precomputed tables and a compiled kernel."""

    def __init__(self, ship: ShipSpec, physics: PhysicsModel | None = None) -> None:
        """Tables of ``ship``; ``physics`` replaces its physics model (e.g. a fouled hull)."""
        self.ship = ship
        self.physics = physics or PhysicsModel(ship)
        c: ShipConstants = self.physics.const
        e, p = ship.engine, ship.propeller
        v_top = c.j_max * (1.5 * e.rpm_max / 60.0) * p.diameter_m / (1.0 - c.max_wake_fraction)
        v_calm = np.linspace(0.0, v_top, _N_CALM)
        r_calm, wake = c.calm_resistance_n(v_calm)
        sqrt_v_wave = np.linspace(0.0, np.sqrt(v_top), _N_WAVE_V)  # uniform in sqrt(V)
        v_wave = sqrt_v_wave**2
        ws_spec = ittc_unit(_PERIOD_GRID_S)
        sw_spec = jonswap_unit(_PERIOD_GRID_S)
        wh, rho = c.wave_hull, c.rho_kg_m3
        u_ws = added_resistance_unit(wh, v_wave[:, None], ws_spec[None], rho)
        u_sw = added_resistance_unit(wh, v_wave[:, None], sw_spec[None], rho)
        v_motion = np.linspace(0.0, min(v_top, 20.0), _N_MOTION_V)
        st = self.physics._stations
        m0_ws = np.empty((_N_MOTION_V, _PERIOD_GRID_S.size, _COS_GRID.size, 3))
        m0_sw = np.empty_like(m0_ws)
        for i, x in enumerate(st.x_m):
            angles = np.degrees(np.arccos(_COS_GRID))
            rao2 = relative_motion_rao2(ship, v_motion[:, None], angles[None, :], x)
            m0_ws[..., i] = np.einsum("vrw,tw->vtr", rao2, ws_spec) * D_OMEGA
            m0_sw[..., i] = np.einsum("vrw,tw->vtr", rao2, sw_spec) * D_OMEGA
        # wind coefficient on a uniform grid of cos(relative angle), -1 (following) .. 1 (head)
        cos_grid = np.linspace(-1.0, 1.0, 2001)
        caa_cos = np.interp(
            np.degrees(np.arccos(cos_grid)), ship.windage.relative_angle_deg, ship.windage.caa
        )
        ref_n = e.rpm_mcr / 60.0
        v_ref = self.physics.evaluate(e.rpm_mcr, 0.0, SeaState.calm()).stw_m_s
        # SFOC on a uniform load grid (exact at the curve's points, linear between)
        sfoc_grid = np.array([0.0, 2.0 / 2000])
        loads = np.linspace(0.0, 2.0, 2001)
        sfoc_uniform = np.interp(loads, e.sfoc_load_fraction, e.sfoc_g_per_kwh)
        for name, tab in (("calm resistance", r_calm), ("wake", wake), ("wave", u_ws),
                          ("swell", u_sw), ("motion", m0_ws), ("swell motion", m0_sw)):
            if not np.all(np.isfinite(tab)):
                raise ShipModelError(f"ship '{ship.name}': non-finite {name} table; check the file")
        par = np.zeros(fk.N_PAR)
        kt, kq = c.curve.kt_poly, c.curve.kq_poly
        values = {
            fk.P_RHO: rho, fk.P_D: p.diameter_m, fk.P_T: c.hm.thrust_deduction,
            fk.P_ETA_R: c.hm.eta_r, fk.P_ETA_S: p.shaft_efficiency, fk.P_JMAX: c.j_max,
            fk.P_WMAX: c.max_wake_fraction, fk.P_KT0: kt[0], fk.P_KT1: kt[1], fk.P_KT2: kt[2],
            fk.P_KT3: kt[3], fk.P_KQ0: kq[0], fk.P_KQ1: kq[1], fk.P_KQ2: kq[2], fk.P_KQ3: kq[3],
            fk.P_AF: ship.windage.frontal_area_m2, fk.P_MCR: e.mcr_kw, fk.P_RPM_MCR: e.rpm_mcr,
            fk.P_RPM_MIN: e.rpm_min, fk.P_RPM_MAX: e.rpm_max,
            fk.P_OVERLOAD: e.overload_power_fraction, fk.P_TORQUE: e.torque_limit_fraction,
            fk.P_DV: v_calm[1], fk.P_NV: _N_CALM, fk.P_WDV: sqrt_v_wave[1], fk.P_WNV: _N_WAVE_V,
            fk.P_T0: _PERIOD_GRID_S[0], fk.P_DT: _PERIOD_GRID_S[1] - _PERIOD_GRID_S[0],
            fk.P_NT: _PERIOD_GRID_S.size, fk.P_SDV: v_motion[1], fk.P_SNV: _N_MOTION_V,
            fk.P_NC: _COS_GRID.size, fk.P_LPP: ship.hull.lpp_m,
            fk.P_MIN_HS: ship.seakeeping.min_hs_imo_check_m,
            fk.P_TROLL: natural_roll_period_s(ship),
            fk.P_TOL: ship.seakeeping.roll_resonance_tolerance,
            fk.P_THR_SLAM: st.threshold_m[0], fk.P_THR_WET: st.threshold_m[1],
            fk.P_THR_PROP: st.threshold_m[2], fk.P_CALM_K: float(v_ref) / ref_n, fk.P_VTOP: v_top,
            fk.P_SURF_KN: 1.8 * np.sqrt(ship.hull.lpp_m), fk.P_POWER_K: 1.0,
        }
        for k, val in values.items():
            par[k] = float(val)
        self._par = par
        self._limits = np.array([
            (1e-6, 1.5 * e.rpm_max), (-720.0, 720.0), (0.0, MAX_WIND_M_S), (0.0, MAX_HS_M),
            (-720.0, 720.0), PERIOD_RANGE_S, (0.0, MAX_HS_M), (-720.0, 720.0), PERIOD_RANGE_S,
            (0.0, MAX_CURRENT_M_S),
        ])
        self._tables: KernelTables = (
            np.ascontiguousarray(r_calm), np.ascontiguousarray(wake),
            np.ascontiguousarray(u_ws), np.ascontiguousarray(u_sw),
            np.ascontiguousarray(m0_ws), np.ascontiguousarray(m0_sw),
            caa_cos,
            sfoc_grid, sfoc_uniform,
        )

    def evaluate(self, rpm: np.ndarray, heading_deg: np.ndarray, sea: SeaState) -> LegPerformance:
        """Evaluate legs (same contract and inputs as ``PhysicsModel.evaluate``)."""
        flat, shape = leg_inputs(rpm, heading_deg, sea)
        n = flat.drive.size
        out_f = np.empty((11, n))
        out_b = np.empty((5, n), dtype=np.bool_)
        chunks = [(0, n)]
        n_threads = min(planner_threads(), _N_THREADS)
        if n >= _THREAD_MIN_LEGS and n_threads >= 2:
            bounds = np.linspace(0, n, n_threads + 1).astype(int)
            chunks = [(int(a), int(b)) for a, b in pairwise(bounds)]
        self._check(flat, chunks)
        args = (*flat, self._par, *self._tables, out_f, out_b)
        if len(chunks) == 1:
            fk.evaluate_kernel(*args, 0, n)
        else:  # the kernel releases the GIL: split the legs over the cores
            futures = [_pool().submit(fk.evaluate_kernel, *args, a, b) for a, b in chunks]
            for fut in futures:
                fut.result()
        f = out_f.reshape((11, *shape))
        b = out_b.reshape((5, *shape))
        return LegPerformance(
            stw_m_s=f[0], sog_m_s=f[1], cog_deg=f[2], brake_power_kw=f[3], fuel_t_per_h=f[4],
            engine_load=f[5], engine_limit_exceeded=b[0], p_slamming=f[8], p_deck_wetness=f[9],
            p_propeller_emergence=f[10], surf_riding=b[1], parametric_roll=b[2],
            synchronous_roll=b[3], high_wave_group=b[4], hs_m=f[6], wind_speed_m_s=f[7],
        )

    def _check(self, flat: LegInputs, chunks: list[tuple[int, int]]) -> None:
        """Range-check the flattened inputs in compiled code; raise like ``check_inputs``."""
        for a, b in chunks:
            field, leg = fk.check_kernel(*flat, self._limits, a, b)
            if field >= 0:
                lo, hi = self._limits[field]
                name = fk.CHECK_FIELDS[field]
                raise InputRangeError(
                    name, f"value at flat index {leg} is NaN or outside the valid range {lo}..{hi}"
                )

    def kernel_arrays(self) -> tuple[np.ndarray, KernelTables, np.ndarray]:
        """(par, tables, limits): the arrays `fast_kernel.evaluate_kernel` takes after the leg
        inputs, and the valid input ranges of `check_kernel`; for compiled callers that run
        the kernel inside their own loops (the GA's population evaluator)."""
        return self._par, self._tables, self._limits

    def rpm_for_speed(
        self, stw_m_s: np.ndarray, heading_deg: np.ndarray, sea: SeaState
    ) -> np.ndarray:
        """Engine RPM for a speed through water (compiled direct inverse, no iteration on V)."""
        flat, shape = leg_inputs(stw_m_s, heading_deg, sea, currents=False)
        check_range("stw_m_s", flat.drive, 0.05, 30.0)
        check_range("heading_deg", flat.heading_deg, -720.0, 720.0)
        check_sea(sea)
        out = np.empty(flat.drive.size)
        r_calm, wake, u_ws, u_sw, _, _, caa, _, _ = self._tables
        bad = rpm_kernel(*flat[:10], self._par, r_calm, wake, u_ws, u_sw, caa, out)
        if bad >= 0:
            raise InputRangeError(
                "stw_m_s", f"at flat index {bad} the following wind pushes the ship faster"
            )
        return out.reshape(shape)


_CACHE: dict[ShipSpec, FastModel] = {}
_LOCK = threading.Lock()
_N_THREADS = min(os.cpu_count() or 1, 4)
_THREAD_MIN_LEGS = 4096
_POOL: ThreadPoolExecutor | None = None


def _pool() -> ThreadPoolExecutor:
    global _POOL  # one lazily created pool per process
    with _LOCK:
        if _POOL is None:
            _POOL = ThreadPoolExecutor(_N_THREADS, thread_name_prefix="shiproute-fast")
        return _POOL


def _forget_pool_in_child() -> None:
    """A forked child has no worker threads: drop the inherited pool (and lock) object."""
    global _POOL, _LOCK
    _POOL = None
    _LOCK = threading.Lock()


os.register_at_fork(after_in_child=_forget_pool_in_child)


def fast_model(ship: ShipSpec) -> FastModel:
    """The fast model of ``ship``, built once per distinct ship (all fields, incl. condition)."""
    with _LOCK:
        model = _CACHE.get(ship)
        if model is None:
            model = FastModel(ship)
            _CACHE[ship] = model
        return model
