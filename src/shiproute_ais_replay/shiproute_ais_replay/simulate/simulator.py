"""Sail a voyage plan through a forecast with the ship model and emit recorded-like states.

The ship steers the great-circle bearing to its next waypoint; every ``model_step_s`` the
performance model is evaluated at the ship's position, heading, RPM and sea state (sampled
from the forecast) and the ship advances along its course over ground at its SOG, landing
exactly on each waypoint. Output states at ``rate_hz`` are interpolated along each step with
sensor-like noise from a seeded generator (GPS ~3 m, SOG/STW 0.05 kn, heading 0.5 deg,
RPM 0.2, fuel 1 %), so the result looks like a real recording but is reproducible.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np
from shiproute_core.geodesy import bearing_deg, destination, distance_m
from shiproute_core.units import M_PER_NM, M_S_PER_KNOT

from ..bag.shipstate import ShipStateRecord
from ..errors import SimulationError
from .voyage_input import VoyagePlan

Sampler = Callable[[np.ndarray, np.ndarray, np.ndarray], dict]
ARRIVAL_M = 50.0  # closer than this to a waypoint counts as reached


@dataclass(frozen=True)
class SimulationOptions:
    """Timing, defaults and noise of a simulation."""

    departure_s: float
    rate_hz: float = 1.0
    model_step_s: float = 600.0
    default_rpm: float = math.nan
    noise: bool = True
    seed: int = 0
    mmsi: int = 0
    max_duration_s: float = 60 * 86400.0


@dataclass
class SimulationSummary:
    """Totals of a finished simulation."""

    states: int = 0
    duration_s: float = 0.0
    distance_nm: float = 0.0
    fuel_t: float = 0.0
    arrived: bool = False


class VoyageSimulator:
    """Stateful simulator; iterate ``states()`` to stream ShipStateRecords."""

    def __init__(self, plan: VoyagePlan, model: Any, ship: Any, opts: SimulationOptions,
                 sampler: Sampler | None = None) -> None:
        if not math.isfinite(opts.departure_s):
            raise SimulationError("departure time is unknown: give --depart or an RTZ etd")
        if opts.rate_hz <= 0 or opts.model_step_s <= 0:
            raise SimulationError("rate_hz and model_step_s must be > 0")
        self.plan, self.model, self.ship, self.opts = plan, model, ship, opts
        self.sampler = sampler
        self.rng = np.random.default_rng(opts.seed)
        self.summary = SimulationSummary()
        self.rpm_min = float(ship.engine.rpm_min)
        self.rpm_max = float(ship.engine.rpm_max)

    def _sea(self, lat: float, lon: float, t_s: float) -> Any:
        from shiproute_planner.ship import SeaState

        if self.sampler is None:
            return SeaState.calm(())
        sample = self.sampler(np.array([lon]), np.array([lat]), np.array([t_s]))
        return SeaState.from_forecast({k: np.asarray(v)[0] for k, v in sample.items()})

    def _rpm(self, leg: int, lat: float, lon: float, t_s: float, heading: float,
             sea: Any) -> float:
        p = self.plan
        rpm = p.leg_rpm[leg]
        if not math.isfinite(rpm):
            stw_kn = p.leg_stw_kn[leg]
            if not math.isfinite(stw_kn) and math.isfinite(p.leg_eta_s[leg]):
                left_m = float(distance_m(lon, lat, p.lon_deg[leg + 1], p.lat_deg[leg + 1]))
                stw_kn = left_m / max(p.leg_eta_s[leg] - t_s, 60.0) / M_S_PER_KNOT
            if math.isfinite(stw_kn):
                rpm = float(self.model.rpm_for_speed(
                    np.array(stw_kn * M_S_PER_KNOT), np.array(heading), sea))
            else:
                rpm = self.opts.default_rpm
        if not math.isfinite(rpm):
            raise SimulationError(f"leg {leg} of {p.source} has no rpm/speed/eta and no --rpm")
        return min(max(rpm, self.rpm_min), self.rpm_max)

    def states(self) -> Iterator[ShipStateRecord]:
        """Stream the voyage's states in time order."""
        p, o = self.plan, self.opts
        lat, lon, t = float(p.lat_deg[0]), float(p.lon_deg[0]), o.departure_s
        leg, period = 0, 1.0 / o.rate_hz
        k_next = 0
        end_s = t + o.max_duration_s
        while leg < len(p.lat_deg) - 1 and t < end_s:
            tlat, tlon = float(p.lat_deg[leg + 1]), float(p.lon_deg[leg + 1])
            left_m = float(distance_m(lon, lat, tlon, tlat))
            if left_m < ARRIVAL_M:
                leg += 1
                continue
            heading = float(bearing_deg(lon, lat, tlon, tlat))
            sea = self._sea(lat, lon, t)
            rpm = self._rpm(leg, lat, lon, t, heading, sea)
            perf = self.model.evaluate(np.array(rpm), np.array(heading), sea)
            sog = float(perf.sog_m_s)
            if sog <= 0.1:
                raise SimulationError(f"ship makes no headway at {lat:.3f},{lon:.3f} ({rpm} rpm)")
            dt, cog, reached = o.model_step_s, float(perf.cog_deg), False
            if sog * dt >= left_m:  # reach the waypoint exactly
                dt, cog, reached = left_m / sog, heading, True
            step = dict(rpm=rpm, heading=heading, cog=cog, sog=sog, stw=float(perf.stw_m_s),
                        fuel=float(perf.fuel_t_per_h))
            k_end = math.ceil((t + dt - o.departure_s) / period - 1e-9)
            times = o.departure_s + period * np.arange(k_next, k_end)
            yield from self._emit(lat, lon, t, times, step)
            k_next = max(k_next, k_end)
            if reached:
                lat2, lon2 = tlat, tlon
            else:
                lon_end, lat_end = destination(lon, lat, cog, sog * dt)
                lon2, lat2 = float(lon_end), float(lat_end)
            self.summary.distance_nm += sog * dt / M_PER_NM
            self.summary.fuel_t += step["fuel"] * dt / 3600.0
            lat, lon, t = float(lat2), float(lon2), t + dt
        self.summary.arrived = leg >= len(p.lat_deg) - 1
        self.summary.duration_s = t - o.departure_s
        if self.summary.arrived:
            yield from self._emit(lat, lon, t, np.array([t]), dict(
                rpm=0.0, heading=float("nan"), cog=float("nan"), sog=0.0, stw=0.0, fuel=0.0))

    def _emit(self, lat0: float, lon0: float, t0: float, times: np.ndarray,
              s: dict) -> Iterator[ShipStateRecord]:
        """States at ``times`` along a step starting at (lat0, lon0, t0)."""
        n = len(times)
        if n == 0:
            return
        dist = s["sog"] * (times - t0)
        cog = s["cog"] if math.isfinite(s["cog"]) else 0.0
        lon, lat = destination(np.full(n, lon0), np.full(n, lat0), np.full(n, cog), dist)
        z = self.rng.standard_normal((6, n)) if self.opts.noise else np.zeros((6, n))
        gps_deg = 3.0 / (60 * M_PER_NM)  # 3 m; a minute of latitude is about a nautical mile
        lat = lat + z[0] * gps_deg
        lon = lon + z[1] * gps_deg / max(math.cos(math.radians(lat0)), 0.01)
        sog_kn = np.maximum(s["sog"] / M_S_PER_KNOT + 0.05 * z[2], 0.0)
        stw_kn = np.maximum(s["stw"] / M_S_PER_KNOT + 0.05 * z[3], 0.0)
        heading = (s["heading"] + 0.5 * z[4]) % 360.0
        rpm = np.maximum(s["rpm"] + 0.2 * z[5], 0.0) if s["rpm"] > 0 else np.zeros(n)
        fuel = s["fuel"] * (1.0 + 0.01 * z[5])
        cond = self.ship.condition
        t_ns = np.round(times * 1e9).astype(np.int64)
        for i in range(n):
            self.summary.states += 1
            yield ShipStateRecord(
                time_ns=int(t_ns[i]), latitude_deg=float(lat[i]),
                longitude_deg=float((lon[i] + 180.0) % 360.0 - 180.0),
                sog_kn=float(sog_kn[i]), cog_deg=float(s["cog"]), heading_deg=float(heading[i]),
                stw_kn=float(stw_kn[i]), shaft_rpm=float(rpm[i]),
                draft_fore_m=float(cond.draft_fore_m), draft_aft_m=float(cond.draft_aft_m),
                fuel_rate_t_per_h=float(fuel[i]), mmsi=self.opts.mmsi,
                nav_status=0 if s["rpm"] > 0 else 5,
            )
