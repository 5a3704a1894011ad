"""Tabulate a learned model into the planner's fast path: the fast model's tables calibrated.

The fast kernel solves thrust = resistance with tables of calm-water resistance, wave added
resistance per Hs^2, the wind coefficient and SFOC. A learned model is turned into the same
tables, so planning with it costs exactly what planning with the ship file costs:

- calm water: at every speed of the calm table the learned RPM (drafts: the model's reference
  drafts) fixes the thrust, hence the effective resistance R_eff(V) = KT(J) rho n^2 D^4 (1 - t)
  the table must hold for the kernel to return that RPM; beyond the training speeds the
  learned residual fades to zero, so the table returns to the ship file's;
- fuel: the kernel's brake power at the learned RPM and the learned fuel rate give an
  effective SFOC per engine load (its ratio to the file's curve held flat beyond the loads
  met in calm water);
- weather: one factor on the wave added resistance and one on the wind resistance, fitted by
  least squares to the learned RPMs over seeded samples of the training range.
The agreement with the learned model itself is measured (`agreement`) and reported.
"""

from __future__ import annotations

import copy

import numpy as np

from ..ship import fast_kernel as fk
from ..ship.fast import FastModel, fast_model
from ..ship.seastate import SeaState
from ..ship.spec import ShipSpec
from .features import FEATURES, KN_M_S
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
    del fore, aft
    return u["stw_kn"] * KN_M_S, sea


def learned_fast_model(ship: ShipSpec, model: LearnedModel, source: str = "",
                       seed: int = 0) -> FastModel:
    """A `FastModel` of ``ship`` whose tables reproduce ``model`` (see the module docstring)."""
    model.check_ship(ship, source or "learned model")
    base = fast_model(ship)
    par, tables, _ = base.kernel_arrays()
    r_calm, wake, u_ws, u_sw, m0_ws, m0_sw, caa, sfoc_x, sfoc_y = tables
    fore, aft = model.reference_draft_fore_m, model.reference_draft_aft_m
    v = np.arange(r_calm.size) * par[fk.P_DV]
    ok = v >= 0.5
    calm = SeaState.calm(int(ok.sum()))
    pred = model.predict(ship, v[ok] / KN_M_S, np.zeros(ok.sum()), fore, aft, calm)
    n_l = pred.rpm / 60.0
    thrust, pb = _thrust_power(base, v[ok], n_l, wake[ok])
    ratio = np.ones_like(v)
    ratio[ok] = thrust / r_calm[ok]
    ratio[~ok] = ratio[ok][0]
    r_new = r_calm * ratio
    # effective SFOC over the engine loads the calm curve passes
    load = np.maximum.accumulate(pb / par[fk.P_MCR])
    file_sfoc = np.interp(load, sfoc_x[0] + np.arange(sfoc_y.size) * (sfoc_x[1] - sfoc_x[0]),
                          sfoc_y)
    sfoc_ratio = (pred.fuel_t_per_h / pb * 1e6) / file_sfoc
    loads = sfoc_x[0] + np.arange(sfoc_y.size) * (sfoc_x[1] - sfoc_x[0])
    keep = np.concatenate([[True], np.diff(load) > 0])
    sfoc_new = sfoc_y * np.interp(loads, load[keep], sfoc_ratio[keep])
    # weather: factors on wave and wind added resistance fitted to the learned RPMs
    rng = np.random.default_rng(seed)
    vw, sea = _weather_samples(model, fore, aft, rng)
    pw = model.predict(ship, vw / KN_M_S, np.zeros(vw.size), fore, aft, sea)
    w_v = np.interp(vw, v, wake)
    thrust_w, _ = _thrust_power(base, vw, pw.rpm / 60.0, w_v)
    r_add = thrust_w - np.interp(vw, v, r_new)
    r_wind, r_wave = base.physics.added_resistance_n(vw, np.zeros(vw.size), sea)
    a = np.column_stack([r_wave, r_wind])
    k_wave, k_wind = np.clip(np.linalg.lstsq(a, r_add, rcond=None)[0], 0.2, 5.0)
    out = copy.copy(base)
    out._tables = (r_new, wake, u_ws * k_wave, u_sw * k_wave, m0_ws, m0_sw, caa * k_wind,
                   sfoc_x, sfoc_new)
    out.learned = model  # type: ignore[attr-defined]
    out.learned_source = source  # type: ignore[attr-defined]
    out.calibration = {  # type: ignore[attr-defined]
        "wave_added_resistance_factor": float(k_wave), "wind_resistance_factor": float(k_wind),
        "calm_resistance_ratio_at_training_speeds": [
            float(np.interp(model.x_lo[0] * KN_M_S, v, ratio)),
            float(np.interp(model.x_hi[0] * KN_M_S, v, ratio))],
    }
    return out


def agreement(fm: FastModel, model: LearnedModel, ship: ShipSpec, stw_kn: np.ndarray,
              heading_deg: np.ndarray, fore: np.ndarray, aft: np.ndarray,
              sea: SeaState) -> dict[str, float]:
    """Mean relative difference [%] of the tabulated model from the learned one (RPM at the
    learned speed, and fuel at that RPM) at the given points."""
    pred = model.predict(ship, stw_kn, heading_deg, fore, aft, sea)
    rpm_t = fm.rpm_for_speed(np.asarray(stw_kn) * KN_M_S, heading_deg, sea)
    fuel_t = fm.evaluate(pred.rpm, heading_deg, sea).fuel_t_per_h
    return {"rpm_mean_diff_pct": float(np.mean(np.abs(rpm_t / pred.rpm - 1)) * 100),
            "fuel_mean_diff_pct": float(np.mean(np.abs(fuel_t / pred.fuel_t_per_h - 1)) * 100)}
