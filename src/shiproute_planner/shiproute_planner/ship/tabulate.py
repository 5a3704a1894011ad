"""Tabulate any performance model into the planner's fast tables (the GA's compiled path).

The fast kernel solves thrust = resistance with tables of calm-water resistance, wave added
resistance per Hs^2, the wind coefficient and SFOC (`FastModel`). Any model with the
`PerformanceModel` contract (Kwon's speed loss, a NetCDF performance profile, ...) is turned
into the same tables of its ship:

- calm water, exactly: the model's speed at a dense RPM grid fixes the thrust the propeller
  gives there (K_T(J) rho n^2 D^4 (1 - t), the kernel's own terms), which is the effective
  resistance the kernel must meet at that speed; the calm table becomes the file's table
  times that ratio (held at its end values beyond the speeds the RPM range reaches). The
  model's fuel rate over the kernel's brake power times the file's SFOC gives a factor per
  engine load; the SFOC table is scaled by it. In calm water the tabulated model then returns
  the model's own speed and fuel at every RPM (to table interpolation).
- weather, fitted: over seeded wind/wave samples (a wind sea grown by the wind, any
  direction, swell-free), the thrust left after calm resistance at the model's speed is
  fitted by least squares as k_wave R_waves + k_wind R_wind with the ship file's STAWAVE-2
  and Blendermann terms (two factors, clipped to 0..5).

How well the tables reproduce the model (speed and fuel at the samples) is measured and kept
in ``calibration`` for the plan's warnings: a model whose weather effect is not a resistance
(Kwon holds power at calm-water output while the speed drops) is reproduced in calm water
and approximately in weather.
"""

from __future__ import annotations

import copy
from typing import Any

import numpy as np

from . import fast_kernel as fk
from .fast import FastModel, fast_model
from .seastate import SeaState
from .spec import ShipSpec

N_CALM_RPM = 240
N_WEATHER_SAMPLES = 800
G_M_S2 = 9.80665


def thrust_and_power(fm: FastModel, v_m_s: np.ndarray, n_rps: np.ndarray,
                     wake: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Thrust x (1 - t) [N] and brake power [kW] at speed v and shaft speed n, computed with
    the fast kernel's own propeller polynomials and efficiencies."""
    par = fm.kernel_arrays()[0]
    d, rho = par[fk.P_D], par[fk.P_RHO]
    j = v_m_s * (1.0 - wake) / (n_rps * d)
    kt = par[fk.P_KT0] + j * (par[fk.P_KT1] + j * (par[fk.P_KT2] + j * par[fk.P_KT3]))
    kq = par[fk.P_KQ0] + j * (par[fk.P_KQ1] + j * (par[fk.P_KQ2] + j * par[fk.P_KQ3]))
    thrust = kt * rho * n_rps**2 * d**4 * (1.0 - par[fk.P_T])
    pb = 2 * np.pi * n_rps * kq * rho * n_rps**2 * d**5 / par[fk.P_ETA_R] / par[fk.P_ETA_S] / 1e3
    return thrust, pb


def weather_samples(ship: ShipSpec, n: int, rng: np.random.Generator
                    ) -> tuple[np.ndarray, np.ndarray, SeaState]:
    """Seeded (rpm, heading, sea) samples: wind 0-25 m/s from any direction, a wind sea of
    0.4-1.1 times the fully developed Pierson-Moskowitz height (Hs = 0.21 U^2 / g) from near
    the wind's direction, its period from the Hs (T = 3.9 Hs^0.5 s, kept in 3-16 s)."""
    e = ship.engine
    rpm = rng.uniform(e.rpm_min, e.rpm_max, n)
    wind = rng.uniform(0.0, min(ship.seakeeping.max_wind_m_s, 25.0), n)
    wind_from = rng.uniform(0.0, 360.0, n)
    hs = np.minimum(0.21 * wind**2 / G_M_S2 * rng.uniform(0.4, 1.1, n), ship.seakeeping.max_hs_m)
    wave_from = (wind_from + rng.normal(0.0, 20.0, n)) % 360.0
    period = np.clip(3.9 * np.sqrt(np.maximum(hs, 0.01)), 3.0, 16.0)
    a = np.radians(wind_from)
    sea = SeaState.from_arrays(wind_u_m_s=-wind * np.sin(a), wind_v_m_s=-wind * np.cos(a),
                               wind_wave_hs_m=hs, wind_wave_from_deg=wave_from,
                               wind_wave_period_s=period)
    return rpm, np.zeros(n), sea


def _calm_tables(base: FastModel, model: Any, v_grid: np.ndarray, r_calm: np.ndarray,
                 wake: np.ndarray, sfoc_x: np.ndarray, sfoc_y: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Calm resistance and SFOC tables that give the model's speed and fuel at every RPM."""
    e = base.ship.engine
    rpm = np.linspace(e.rpm_min, e.rpm_max, N_CALM_RPM)
    perf = model.evaluate(rpm, np.zeros(rpm.size), SeaState.calm(rpm.size))
    v = np.asarray(perf.stw_m_s, dtype=float)
    ok = np.isfinite(v) & (v > 0.05)
    order = np.argsort(v[ok])
    v, rpm_ok = v[ok][order], rpm[ok][order]
    fuel = np.asarray(perf.fuel_t_per_h, dtype=float)[ok][order]
    keep = np.concatenate([[True], np.diff(v) > 1e-6])  # strictly increasing speeds
    v, rpm_ok, fuel = v[keep], rpm_ok[keep], fuel[keep]
    thrust, pb = thrust_and_power(base, v, rpm_ok / 60.0, np.interp(v, v_grid, wake))
    ratio = thrust / np.interp(v, v_grid, r_calm)
    r_new = r_calm * np.interp(v_grid, v, ratio)  # held at the end ratios beyond
    par = base.kernel_arrays()[0]
    loads = sfoc_x[0] + np.arange(sfoc_y.size) * (sfoc_x[1] - sfoc_x[0])
    load = pb / par[fk.P_MCR]
    f_ratio = fuel / (pb * np.interp(load, loads, sfoc_y) * 1e-6)
    by_load = np.argsort(load)
    sfoc_new = sfoc_y * np.interp(loads, load[by_load], f_ratio[by_load])
    return r_new, sfoc_new


def tabulated_model(ship: ShipSpec, model: Any, label: str, seed: int = 0) -> FastModel:
    """A `FastModel` of ``ship`` whose tables reproduce ``model`` (module docstring); its
    ``calibration`` says how closely, ``source_model`` keeps the model for direct checks."""
    base = fast_model(ship)
    par, tables, _ = base.kernel_arrays()
    r_calm, wake, u_ws, u_sw, m0_ws, m0_sw, caa, sfoc_x, sfoc_y = tables
    v_grid = np.arange(r_calm.size) * par[fk.P_DV]
    r_new, sfoc_new = _calm_tables(base, model, v_grid, r_calm, wake, sfoc_x, sfoc_y)
    calm = copy.copy(base)
    calm._tables = (r_new, wake, u_ws, u_sw, m0_ws, m0_sw, caa, sfoc_x, sfoc_new)
    rng = np.random.default_rng(seed)
    rpm, hdg, sea = weather_samples(ship, N_WEATHER_SAMPLES, rng)
    perf = model.evaluate(rpm, hdg, sea)
    v = np.asarray(perf.stw_m_s, dtype=float)
    thrust, _ = thrust_and_power(base, v, rpm / 60.0, np.interp(v, v_grid, wake))
    r_wind, r_wave = base.physics.added_resistance_n(v, hdg, sea)
    residual = thrust - np.interp(v, v_grid, r_new)
    # fitted where a ship sails: at least half its calm-water speed at that RPM (beyond, e.g.
    # Kwon's loss formula extrapolated past Beaufort 9, a ship heaves to or is routed away)
    v_calm = calm.evaluate(rpm, hdg, SeaState.calm(rpm.size)).stw_m_s
    sailing = v > 0.5 * v_calm
    a = np.column_stack([r_wave, r_wind])[sailing]
    k_wave, k_wind = np.clip(np.linalg.lstsq(a, residual[sailing], rcond=None)[0], 0.0, 5.0)
    out = copy.copy(calm)
    out._tables = (r_new, wake, u_ws * k_wave, u_sw * k_wave, m0_ws, m0_sw, caa * k_wind,
                   sfoc_x, sfoc_new)
    out._par = par.copy()  # the base model's vector is shared by every copy: never edit it
    out._par[fk.P_POWER_K] = power_share(out, rpm[sailing], hdg[sailing], sea.take(sailing),
                                         np.asarray(perf.fuel_t_per_h, float)[sailing])
    got = out.evaluate(rpm, hdg, sea)
    calm_rpm = np.linspace(ship.engine.rpm_min, ship.engine.rpm_max, 25)
    calm_ref = model.evaluate(calm_rpm, np.zeros(25), SeaState.calm(25))
    calm_got = out.evaluate(calm_rpm, np.zeros(25), SeaState.calm(25))
    out.source_model = model  # type: ignore[attr-defined]
    out.calibration = {  # type: ignore[attr-defined]
        "model": label,
        "wave_added_resistance_factor": float(k_wave),
        "weather_power_share": float(out._par[fk.P_POWER_K]),
        "wind_resistance_factor": float(k_wind),
        "calm_fuel_max_diff_pct": _max_pct(calm_got.fuel_t_per_h, calm_ref.fuel_t_per_h),
        "calm_speed_max_diff_pct": _max_pct(calm_got.stw_m_s, calm_ref.stw_m_s),
        "weather_speed_median_diff_pct": _pct(got.stw_m_s[sailing], v[sailing], 50),
        "weather_speed_p90_diff_pct": _pct(got.stw_m_s[sailing], v[sailing], 90),
        "weather_fuel_median_diff_pct": _pct(got.fuel_t_per_h[sailing],
                                             perf.fuel_t_per_h[sailing], 50),
        "weather_fuel_p90_diff_pct": _pct(got.fuel_t_per_h[sailing],
                                          perf.fuel_t_per_h[sailing], 90),
        "weather_samples_sailing": int(sailing.sum()),
        "weather_samples": int(sailing.size),
    }
    return out


def power_share(fm: FastModel, rpm: np.ndarray, hdg: np.ndarray, sea: SeaState,
                fuel_t_per_h: np.ndarray) -> float:
    """The share of the weather's extra shaft power the model burns (fast_kernel.P_POWER_K):
    the tables' fuel is nearly linear in it, so it is the least-squares fit (relative errors)
    of the model's fuel between the tables' fuel at share 0 (Kwon's premise: calm-water
    output held) and at share 1 (the propeller's torque in the loaded condition)."""
    par = fm.kernel_arrays()[0]
    fuel = []
    for share in (0.0, 1.0):
        par[fk.P_POWER_K] = share
        fuel.append(np.asarray(fm.evaluate(rpm, hdg, sea).fuel_t_per_h, float))
    f0, f1 = fuel[0] / fuel_t_per_h, fuel[1] / fuel_t_per_h
    den = float(np.sum((f1 - f0) ** 2))
    share = float(np.sum((1.0 - f0) * (f1 - f0)) / den) if den > 0.0 else 1.0
    return float(np.clip(share, 0.0, 2.0))


def _max_pct(a: Any, b: Any) -> float:
    return float(np.max(np.abs(np.asarray(a) / np.asarray(b) - 1.0)) * 100.0)


def _pct(a: Any, b: Any, q: float) -> float:
    return float(np.percentile(np.abs(np.asarray(a) / np.asarray(b) - 1.0), q) * 100.0)


def calibration_note(model: Any) -> str:
    """One line for the plan's warnings: how closely the fast tables follow the model."""
    c = getattr(model, "calibration", None)
    if not c or "calm_fuel_max_diff_pct" not in c:
        return ""
    return (f"ship model {c['model']} tabulated for the fast path: calm water within "
            f"{c['calm_fuel_max_diff_pct']:.2f} % fuel / {c['calm_speed_max_diff_pct']:.2f} % "
            "speed; in wind and waves (Beaufort 0-10) median "
            f"{c['weather_fuel_median_diff_pct']:.1f} % fuel, "
            f"{c['weather_speed_median_diff_pct']:.1f} % speed, 90th percentile "
            f"{c['weather_fuel_p90_diff_pct']:.1f} % / {c['weather_speed_p90_diff_pct']:.1f} % "
            f"(added resistance x "
            f"{c['wave_added_resistance_factor']:.2f} waves, x {c['wind_resistance_factor']:.2f}"
            " wind)")
