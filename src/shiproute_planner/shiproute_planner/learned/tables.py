"""Tabulate a learned model into the planner's fast path: the fast model's tables calibrated.

The fast kernel solves thrust = resistance with tables of calm-water resistance, wave added
resistance per Hs^2, the wind coefficient and SFOC. A learned model is turned into the same
tables, so planning with it costs exactly what planning with the ship file costs:

- resistance: over seeded samples of the training range (speed and weather), the learned RPM
  fixes the thrust, hence the effective resistance KT(J) rho n^2 D^4 (1 - t) the kernel must
  see to return that RPM; it is fitted by least squares as a(V) R_calm(V) + k_wave R_waves +
  k_wind R_wind with the ship file's terms, a(V) quadratic in speed (hull fouling, trim) and
  two constant factors (added resistance); the calm table becomes a(V) R_calm(V), fading back
  to the file's beyond the training speeds (over ``fallback_std`` standard deviations, as the
  learned model does), the wave and wind tables are scaled by k_wave and k_wind;
- fuel: at the same samples the learned fuel rate over the kernel's brake power times the
  file's SFOC gives a ratio, fitted quadratic in engine load; the SFOC table is the file's
  times that ratio (held at the ends of the loads seen, fading to 1 beyond them).
The agreement with the learned model itself is measured (`agreement`) and reported.
"""

from __future__ import annotations

import copy

import numpy as np
from shiproute_core.units import M_S_PER_KNOT

from ..ship import fast_kernel as fk
from ..ship.fast import FastModel, fast_model
from ..ship.seastate import SeaState
from ..ship.spec import ShipSpec
from .features import DRAFT_STEP_M, FEATURES, at_drafts
from .model import LearnedModel

N_WEATHER_SAMPLES = 600


def _thrust_power(fm: FastModel, v: np.ndarray, n_rps: np.ndarray,
                  wake: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Thrust x (1 - t) [N] and brake power [kW] at speed v and shaft speed n (kernel's terms)."""
    par = fm.kernel_arrays()[0]
    d, rho = par[fk.P_D], par[fk.P_RHO]
    j = v * (1.0 - wake) / (n_rps * d)
    kt = par[fk.P_KT0] + j * (par[fk.P_KT1] + j * (par[fk.P_KT2] + j * par[fk.P_KT3]))
    kq = par[fk.P_KQ0] + j * (par[fk.P_KQ1] + j * (par[fk.P_KQ2] + j * par[fk.P_KQ3]))
    thrust = kt * rho * n_rps**2 * d**4 * (1.0 - par[fk.P_T])
    pb = 2 * np.pi * n_rps * kq * rho * n_rps**2 * d**5 / par[fk.P_ETA_R] / par[fk.P_ETA_S] / 1e3
    return thrust, pb


def _weather_samples(model: LearnedModel, fore: float, aft: float,
                     rng: np.random.Generator) -> tuple[np.ndarray, SeaState]:
    """Seeded speeds (m/s) and sea states (heading 0) spread over the training ranges."""
    lo, hi = model.x_lo, model.x_hi
    u = {f: rng.uniform(lo[i], hi[i], N_WEATHER_SAMPLES) for i, f in enumerate(FEATURES)}
    wind_from = np.arccos(np.clip(u["cos_rel_wind"], -1, 1)) * rng.choice([-1, 1], u["hs_m"].size)
    wave_from = np.degrees(np.arccos(np.clip(u["cos_rel_wave"], -1, 1)))
    sea = SeaState.from_arrays(
        wind_u_m_s=-u["wind_speed_m_s"] * np.sin(wind_from),
        wind_v_m_s=-u["wind_speed_m_s"] * np.cos(wind_from),
        wind_wave_hs_m=u["hs_m"], wind_wave_from_deg=wave_from,
        wind_wave_period_s=np.maximum(u["wave_period_s"], 1.0))
    del fore, aft  # the samples are evaluated at the model's reference drafts by the caller
    return u["stw_kn"] * M_S_PER_KNOT, sea


def learned_fast_model(ship: ShipSpec, model: LearnedModel, source: str = "",
                       seed: int = 0) -> FastModel:
    """A `FastModel` of ``ship`` whose tables reproduce ``model`` (see the module docstring)."""
    model.check_ship(ship, source or "learned model")
    fore, aft = model.reference_draft_fore_m, model.reference_draft_aft_m
    step = DRAFT_STEP_M  # the drafts the learned model's prior uses
    base = fast_model(at_drafts(ship, round(round(fore / step) * step, 3),
                                round(round(aft / step) * step, 3)))
    par, tables, _ = base.kernel_arrays()
    r_calm, wake, u_ws, u_sw, m0_ws, m0_sw, caa, sfoc_x, sfoc_y = tables
    v_grid = np.arange(r_calm.size) * par[fk.P_DV]
    rng = np.random.default_rng(seed)
    v, sea = _weather_samples(model, fore, aft, rng)
    pred = model.predict(ship, v / M_S_PER_KNOT, np.zeros(v.size), fore, aft, sea)
    w_v = np.interp(v, v_grid, wake)
    thrust, pb = _thrust_power(base, v, pred.rpm / 60.0, w_v)
    r_wind, r_wave = base.physics.added_resistance_n(v, np.zeros(v.size), sea)
    rc = np.interp(v, v_grid, r_calm)
    v_lo, v_hi = model.x_lo[0] * M_S_PER_KNOT, model.x_hi[0] * M_S_PER_KNOT
    mid, half = 0.5 * (v_lo + v_hi), max(0.5 * (v_hi - v_lo), 0.1)
    z = (v - mid) / half
    a = np.column_stack([rc, rc * z, rc * z**2, r_wave, r_wind])
    coef = np.linalg.lstsq(a, thrust, rcond=None)[0]
    k_wave, k_wind = np.clip(coef[3:], 0.2, 5.0)
    zg = (np.clip(v_grid, v_lo, v_hi) - mid) / half
    a_grid = coef[0] + coef[1] * zg + coef[2] * zg**2
    beyond = np.maximum(v_lo - v_grid, v_grid - v_hi) / (model.x_std[0] * M_S_PER_KNOT)
    fade = np.clip(1.0 - np.maximum(beyond, 0.0) / model.fallback_std, 0.0, 1.0)
    ratio = 1.0 + fade * (a_grid - 1.0)
    r_new = r_calm * ratio
    # fuel: learned fuel over the kernel's power x the file's SFOC, quadratic in load
    loads = sfoc_x[0] + np.arange(sfoc_y.size) * (sfoc_x[1] - sfoc_x[0])
    load = pb / par[fk.P_MCR]
    f_ratio = pred.fuel_t_per_h / (pb * np.interp(load, loads, sfoc_y) * 1e-6)
    l_lo, l_hi = float(np.min(load)), float(np.max(load))
    lm, lh = 0.5 * (l_lo + l_hi), max(0.5 * (l_hi - l_lo), 1e-3)
    lz = (load - lm) / lh
    b = np.linalg.lstsq(np.column_stack([np.ones_like(lz), lz, lz**2]), f_ratio, rcond=None)[0]
    lzg = (np.clip(loads, l_lo, l_hi) - lm) / lh
    fade_l = np.clip(1.0 - np.maximum(np.maximum(l_lo - loads, loads - l_hi), 0.0) / lh,
                     0.0, 1.0)
    sfoc_new = sfoc_y * (1.0 + fade_l * (b[0] + b[1] * lzg + b[2] * lzg**2 - 1.0))
    out = copy.copy(base)
    out._tables = (r_new, wake, u_ws * k_wave, u_sw * k_wave, m0_ws, m0_sw, caa * k_wind,
                   sfoc_x, sfoc_new)
    out.learned = model  # type: ignore[attr-defined]
    out.learned_source = source  # type: ignore[attr-defined]
    out.calibration = {  # type: ignore[attr-defined]
        "wave_added_resistance_factor": float(k_wave), "wind_resistance_factor": float(k_wind),
        "calm_resistance_factor_at_training_speeds": [float(a_grid[np.argmin(abs(v_grid - x))])
                                                      for x in (v_lo, mid, v_hi)],
        "sfoc_factor_at_loads": [float(b[0] + b[1] * x + b[2] * x * x) for x in (-1, 0, 1)],
    }
    return out


def agreement(fm: FastModel, model: LearnedModel, ship: ShipSpec, stw_kn: np.ndarray,
              heading_deg: np.ndarray, fore: np.ndarray, aft: np.ndarray,
              sea: SeaState) -> dict[str, float]:
    """Mean relative difference [%] of the tabulated model from the learned one (RPM at the
    learned speed, and fuel at that RPM) at the given points."""
    pred = model.predict(ship, stw_kn, heading_deg, fore, aft, sea)
    rpm_t = fm.rpm_for_speed(np.asarray(stw_kn) * M_S_PER_KNOT, heading_deg, sea)
    fuel_t = fm.evaluate(pred.rpm, heading_deg, sea).fuel_t_per_h
    return {"rpm_mean_diff_pct": float(np.mean(np.abs(rpm_t / pred.rpm - 1)) * 100),
            "fuel_mean_diff_pct": float(np.mean(np.abs(fuel_t / pred.fuel_t_per_h - 1)) * 100)}
