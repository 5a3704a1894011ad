"""Ship-model benchmark: Holtrop-Mennen check, 77 rpm calibration, fast-model speed and error."""

from __future__ import annotations

import argparse
import os
import time

import numpy as np
from shiproute_core.bench_report import print_figures
from shiproute_core.units import M_S_PER_KNOT

from ...ship import PhysicsModel, SeaState, fast_model, load_ship
from ...ship.holtrop_mennen import HMHull, coefficients, resistance
from ...ship.propeller import kt_kq

# Holtrop & Mennen (1982) worked example: published values
_HM_HULL = HMHull(
    lwl_m=205.0, breadth_m=32.0, draft_fore_m=10.0, draft_aft_m=10.0, volume_m3=37500.0,
    midship_coefficient=0.98, waterplane_coefficient=0.75, lcb_percent=-0.75, bulb_area_m2=20.0,
    bulb_center_height_m=4.0, transom_area_m2=16.0, appendage_area_m2=50.0,
    appendage_form_factor=1.5, stern_shape_coefficient=10.0, wetted_surface_m2=7381.45,
    propeller_diameter_m=8.0, propeller_area_ratio=0.75,
)
_HM_PUBLISHED = {"fn": 0.2868, "form_factor": 1.156, "c1": 1.398, "m1": -2.1274, "lam": 0.6513,
                 "r_friction_kn": 869.63, "r_wave_kn": 557.11, "r_correlation_kn": 221.98}


def hm_errors() -> dict[str, float]:
    """Relative error of each published Holtrop-Mennen example value."""
    c = coefficients(_HM_HULL)
    r = resistance(_HM_HULL, c, np.array([25.0 * M_S_PER_KNOT]), 1025.0, 1.1883e-6)
    ours = {"fn": float(r.froude[0]), "form_factor": c.form_factor, "c1": float(c.c1),
            "m1": c.m1, "lam": c.lam, "r_friction_kn": float(r.r_friction_n[0]) / 1e3,
            "r_wave_kn": float(r.r_wave_n[0]) / 1e3,
            "r_correlation_kn": float(r.r_correlation_n[0]) / 1e3}
    return {k: abs(ours[k] / v - 1.0) for k, v in _HM_PUBLISHED.items()}


def random_legs(rng: np.random.Generator, n: int, rpm_max: float):
    """Random RPMs, headings and weather (wind, wind sea, swell, current) for n legs."""
    sea = SeaState.from_arrays(
        wind_u_m_s=rng.uniform(-20, 20, n), wind_v_m_s=rng.uniform(-20, 20, n),
        wind_wave_hs_m=rng.uniform(0, 7, n), wind_wave_from_deg=rng.uniform(0, 360, n),
        wind_wave_period_s=rng.uniform(2.5, 11, n), swell_hs_m=rng.uniform(0, 5, n),
        swell_from_deg=rng.uniform(0, 360, n), swell_period_s=rng.uniform(6, 18, n),
        current_u_m_s=rng.uniform(-1.5, 1.5, n), current_v_m_s=rng.uniform(-1.5, 1.5, n),
    )
    return rng.uniform(0.3, 1.0, n) * rpm_max, rng.uniform(0, 360, n), sea


def run(ship_name: str, n_legs: int, n_check: int, seed: int) -> dict[str, object]:
    """Compute every benchmark figure."""
    rng = np.random.default_rng(seed)
    load_before = os.getloadavg()[0]
    ship = load_ship(ship_name)
    physics = PhysicsModel(ship)
    calm = physics.evaluate(77.0, 0.0, SeaState.calm())
    t0 = time.perf_counter()
    fm = fast_model(ship)
    build_s = time.perf_counter() - t0
    rpm, hdg, sea = random_legs(rng, n_check, ship.engine.rpm_max)
    fm.evaluate(rpm[:10], hdg[:10], SeaState(**{k: v[:10] for k, v in vars(sea).items()}))
    t0 = time.perf_counter()
    direct = physics.evaluate(rpm, hdg, sea)
    direct_rate = n_check / (time.perf_counter() - t0)
    fast = fm.evaluate(rpm, hdg, sea)
    moving = direct.stw_m_s > 0.5
    errs = {k: float(np.max(np.abs(getattr(fast, k)[moving] / getattr(direct, k)[moving] - 1)))
            for k in ("stw_m_s", "brake_power_kw", "fuel_t_per_h")}
    rpm, hdg, sea = random_legs(rng, n_legs, ship.engine.rpm_max)
    times, cpu = [], []
    for _ in range(5):
        t0, c0 = time.perf_counter(), time.process_time()
        fm.evaluate(rpm, hdg, sea)
        times.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
    small = SeaState(**{k: v[:500] for k, v in vars(sea).items()})
    t0 = time.perf_counter()
    for _ in range(50):
        fm.evaluate(rpm[:500], hdg[:500], small)
    per_call_500_us = (time.perf_counter() - t0) / 50 * 1e6
    j = np.linspace(0.05, 1.0, 400)
    kt, kq = kt_kq(j, 1.0, 0.70, 4)
    eta = kt * j / (2 * np.pi * kq)
    hm = hm_errors()
    return {
        "ship": ship_name,
        "hm_max_rel_err": max(hm.values()),
        "hm_rel_err": hm,
        "speed_kn_at_77rpm_calm": float(calm.stw_m_s) / M_S_PER_KNOT,
        "fuel_t_per_day_at_77rpm_calm": float(calm.fuel_t_per_h) * 24.0,
        "brake_power_kw_at_77rpm_calm": float(calm.brake_power_kw),
        "reference_voyage_hours_calm": 5248.0 / (float(calm.stw_m_s) / M_S_PER_KNOT),
        "leg_evals_per_s": n_legs / min(times),
        "leg_evals_per_s_median": n_legs / float(np.median(times)),
        # CPU-time rate of one core: independent of other processes competing for the cores
        "leg_evals_per_cpu_s": n_legs / min(cpu),
        "n_legs": n_legs,
        "call_500_legs_us": per_call_500_us,
        "fast_model_build_s": build_s,
        "fast_model_max_rel_err": max(errs.values()),
        "fast_model_rel_err": errs,
        "direct_leg_evals_per_s": direct_rate,
        "b4_70_kt0": float(kt_kq(np.array([0.0]), 1.0, 0.70, 4)[0][0]),
        "b4_70_10kq0": float(10 * kt_kq(np.array([0.0]), 1.0, 0.70, 4)[1][0]),
        "b4_70_eta_max": float(eta.max()),
        "b4_70_j_at_eta_max": float(j[np.argmax(eta)]),
        "load_average_1min": load_before,
        "cpu_count": os.cpu_count(),
    }


def main(argv: list[str]) -> int:
    """``shiproute bench ship [--json] [--legs N] [--ship NAME]``."""
    ap = argparse.ArgumentParser(prog="shiproute bench ship", description=__doc__)
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    ap.add_argument("--legs", type=int, default=100_000, help="legs for the throughput figure")
    ap.add_argument("--check-legs", type=int, default=2000, help="legs for fast-vs-direct error")
    ap.add_argument("--ship", default="container_4600teu")
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args(argv)
    result = run(args.ship, args.legs, args.check_legs, args.seed)
    print_figures(result, args.json)
    return 0
