"""Realistic records of a ship whose hull differs from its ship file, for training and tests.

The true ship is the ship file's with fouling (frictional resistance incl. form factor times
1 + ``friction_increase``) and another trim (``extra_trim_m`` more by the stern, same mean
draft; the mean draft varies a little per voyage). It sails voyages of several legs at
different RPMs through a forecast (`simulate.VoyageSimulator`, the physics model, one record
a minute), and the records then get what ISO 19030 cleaning is for: fuel-meter noise and bias,
draft-gauge bias, dropouts (single fields and whole outages), stuck sensors, spikes and
manoeuvres (RPM and speed changes, course alterations with rudder). Seeded throughout.
"""

from __future__ import annotations

import csv
import dataclasses
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from shiproute_core.units import M_PER_NM

from .records import COLUMNS, Records


@dataclass(frozen=True)
class HullChange:
    """How the true ship differs from its ship file."""

    friction_increase: float = 0.15
    extra_trim_m: float = 1.5  # more by the stern than the file's condition
    mean_draft_spread_m: float = 0.3  # +- per voyage


@dataclass(frozen=True)
class Corruption:
    """Rates of sensor and operating artefacts (per record unless stated)."""

    fuel_noise: float = 0.015  # relative, on top of the simulator's 1 %
    fuel_bias: float = 0.005
    draft_bias_m: float = 0.05
    dropout: float = 0.01
    outages_per_voyage: int = 1  # 30 min without any reading
    stuck_per_voyage: int = 2  # RPM or fuel frozen for 20-40 min
    spike: float = 0.003
    manoeuvres_per_voyage: int = 3  # 30-60 min of RPM/speed changes and course alterations


def fouled_physics(ship, friction_increase: float):
    """Physics model of ``ship`` with its frictional resistance raised by the given fraction."""
    from shiproute_planner.ship.holtrop_mennen import resistance
    from shiproute_planner.ship.hull import ShipConstants, ship_constants
    from shiproute_planner.ship.physics import PhysicsModel

    @dataclass(frozen=True)
    class FouledConstants(ShipConstants):
        friction_increase: float = 0.0

        def calm_resistance_n(self, speed_m_s):
            r = resistance(self.hm_hull, self.hm, speed_m_s, self.rho_kg_m3, self.nu_m2_s)
            extra = self.friction_increase * r.r_friction_n * self.hm.form_factor
            return r.r_total_n + extra, r.wake_fraction

    model = PhysicsModel(ship)
    base = ship_constants(ship)
    model.const = FouledConstants(**{f.name: getattr(base, f.name)
                                     for f in dataclasses.fields(base)},
                                  friction_increase=friction_increase)
    return model


def true_ship(ship, change: HullChange, mean_draft_offset_m: float = 0.0):
    """(ShipSpec at the true drafts, its fouled model: tabulated, < 0.5 % from the direct
    physics solve, which would take minutes for a few voyages)."""
    c = ship.condition
    mean = 0.5 * (c.draft_fore_m + c.draft_aft_m) + mean_draft_offset_m
    trim = (c.draft_aft_m - c.draft_fore_m) + change.extra_trim_m
    extra_t = (1.025 * ship.hull.waterplane_coefficient * ship.hull.lwl_m * ship.hull.breadth_m
               * mean_draft_offset_m)
    cond = dataclasses.replace(c, name=f"{c.name} (true)", draft_fore_m=mean - trim / 2,
                               draft_aft_m=mean + trim / 2,
                               displacement_t=c.displacement_t + extra_t)
    spec = dataclasses.replace(ship, condition=cond,
                               content_hash=ship.content_hash + f"#true{mean:.3f}/{trim:.3f}")
    from shiproute_planner.ship.fast import FastModel

    return spec, FastModel(spec, fouled_physics(spec, change.friction_increase))


def _plan(rng: np.random.Generator, eastbound: bool, legs: int, leg_nm: float):
    from shiproute_core.geodesy import destination

    from ..simulate.voyage_input import VoyagePlan

    lat = [float(rng.uniform(30.0, 44.0))]
    lon = [float(rng.uniform(150.0, 165.0) if eastbound else rng.uniform(205.0, 220.0))]
    base = 90.0 if eastbound else 270.0
    for _ in range(legs):
        hdg = base + rng.uniform(-35.0, 35.0)
        if lat[-1] > 45.0:
            hdg = base + (20.0 if eastbound else -20.0)
        if lat[-1] < 28.0:
            hdg = base - (20.0 if eastbound else -20.0)
        lo, la = destination(lon[-1], lat[-1], hdg, leg_nm * M_PER_NM)
        lat.append(float(la))
        lon.append(float(lo))
    rpm = rng.uniform(50.0, 92.0, legs)
    nan = np.full(legs, math.nan)
    return VoyagePlan(np.array(lat), np.array(lon), rpm, nan, nan, math.nan,
                      source="synthetic voyage")


def simulate_fleet_records(ship, forecast, n_voyages: int, start_s: float, seed: int = 0,
                           legs: int = 3, leg_nm: float = 300.0, change: HullChange = HullChange(),
                           corruption: Corruption = Corruption(), rate_hz: float = 1 / 60.0
                           ) -> Records:
    """Records of ``n_voyages`` consecutive voyages of the true ship (see the module doc)."""
    import numba
    from shiproute_weather.sampling.sampler import ForecastSampler


    rng = np.random.default_rng(seed)
    sampler = ForecastSampler(forecast).sample if forecast is not None else None
    threads = numba.get_num_threads()
    numba.set_num_threads(1)  # one point per call: waking the thread pool cost 25 ms a call
    try:
        return _simulate(ship, sampler, n_voyages, start_s, rng, legs, leg_nm, change,
                         corruption, rate_hz)
    finally:
        numba.set_num_threads(threads)


def _simulate(ship, sampler, n_voyages, start_s, rng, legs, leg_nm, change, corruption,
              rate_hz) -> Records:
    from ..simulate.simulator import SimulationOptions, VoyageSimulator

    parts = []
    t = start_s
    for v in range(n_voyages):
        spec, physics = true_ship(ship, change, float(rng.uniform(-1, 1))
                                  * change.mean_draft_spread_m)
        plan = _plan(rng, v % 2 == 0, legs, leg_nm)
        opts = SimulationOptions(departure_s=t, rate_hz=rate_hz, model_step_s=600.0,
                                 seed=int(rng.integers(1 << 31)))
        sim = VoyageSimulator(plan, physics, spec, opts, sampler)
        recs = list(sim.states())
        cols = {c: np.array([getattr(r, c) if c != "time_s" else r.time_ns / 1e9 for r in recs],
                            dtype=float) for c in COLUMNS[:11]}
        n = cols["time_s"].size
        cols["rudder_angle_deg"] = rng.normal(0.0, 0.5, n)
        cols["water_depth_m"] = np.full(n, math.nan)
        cols["voyage"] = np.full(n, float(v))
        parts.append(corrupt(cols, rng, corruption))
        t = cols["time_s"][-1] + rng.uniform(6.5, 12.0) * 3600.0
    merged = {c: np.concatenate([p[c] for p in parts]) for c in COLUMNS}
    return Records(merged, ("synthetic",))


def corrupt(cols: dict[str, np.ndarray], rng: np.random.Generator,
            k: Corruption) -> dict[str, np.ndarray]:
    """Sensor noise, bias, dropouts, outages, stuck values, spikes and manoeuvres."""
    c = {key: v.copy() for key, v in cols.items()}
    n = c["time_s"].size
    t = c["time_s"] - c["time_s"][0]
    for _ in range(k.manoeuvres_per_voyage):
        a = int(rng.integers(0, max(n - 60, 1)))
        m = slice(a, min(a + int(rng.integers(30, 61)), n))
        ratio = 1.0 + 0.12 * np.sin(2 * np.pi * t[m] / 600.0)
        c["shaft_rpm"][m] *= ratio
        c["fuel_rate_t_per_h"][m] *= ratio**3
        for q in ("sog_kn", "stw_kn"):
            c[q][m] *= ratio
        turn = 25.0 * np.sin(2 * np.pi * t[m] / 1200.0)
        c["heading_deg"][m] = (c["heading_deg"][m] + turn) % 360.0
        c["cog_deg"][m] = (c["cog_deg"][m] + turn) % 360.0
        c["rudder_angle_deg"][m] = 15.0 * np.cos(2 * np.pi * t[m] / 1200.0)
    c["fuel_rate_t_per_h"] *= (1.0 + k.fuel_bias) * (1.0 + k.fuel_noise * rng.standard_normal(n))
    c["draft_fore_m"] += k.draft_bias_m
    c["draft_aft_m"] += k.draft_bias_m
    for _ in range(k.stuck_per_voyage):
        a = int(rng.integers(0, max(n - 40, 1)))
        q = "shaft_rpm" if rng.random() < 0.5 else "fuel_rate_t_per_h"
        c[q][a:a + int(rng.integers(20, 41))] = c[q][a]
    spikes = np.flatnonzero(rng.random(n) < k.spike)
    for i in spikes:
        if rng.random() < 0.5:
            c["fuel_rate_t_per_h"][i] *= rng.uniform(2.0, 5.0)
        else:
            c["shaft_rpm"][i] += rng.uniform(15.0, 40.0)
    fields = ("sog_kn", "heading_deg", "stw_kn", "shaft_rpm", "fuel_rate_t_per_h", "cog_deg")
    for i in np.flatnonzero(rng.random(n) < k.dropout):
        c[fields[int(rng.integers(len(fields)))]][i] = math.nan
    for _ in range(k.outages_per_voyage):
        a = int(rng.integers(0, max(n - 30, 1)))
        for q in COLUMNS[1:11]:
            c[q][a:a + 30] = math.nan
    return c


def write_csv(records: Records, path: str | Path) -> None:
    """CSV sensor log with units in the header (the format `records.read_csv` reads)."""
    cols = records.columns
    names = ("latitude_deg", "longitude_deg", "sog_kn", "cog_deg", "heading_deg", "stw_kn",
             "shaft_rpm", "fuel_rate_t_per_h", "draft_fore_m", "draft_aft_m",
             "rudder_angle_deg", "voyage")
    with Path(path).open("w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(("time_s", *names))
        for i in range(len(records)):
            row = [f"{cols['time_s'][i]:.3f}"]
            for q in names:
                x = cols[q][i]
                row.append("" if not math.isfinite(x) else
                           str(int(x)) if q == "voyage" else f"{x:.6g}")
            w.writerow(row)


def write_bag(records: Records, path: str | Path) -> dict[str, int]:
    """MCAP bag of ShipState messages (rudder angle and voyage are not ShipState fields)."""
    from ..bag.shipstate import ShipStateRecord
    from ..bag.statebag import write_states

    cols = records.columns

    def states():
        for i in range(len(records)):
            yield ShipStateRecord(
                time_ns=round(float(cols["time_s"][i]) * 1e9),
                **{q: float(cols[q][i]) for q in COLUMNS[1:11]},
                nav_status=0 if cols["shaft_rpm"][i] > 0 else 15)

    return write_states(states(), path, with_fix=False)
