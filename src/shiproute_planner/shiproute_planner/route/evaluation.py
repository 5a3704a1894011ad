"""Route evaluation result shared by every method, and its assembly from per-leg arrays.

Both entry points (`generate.evaluate_genes` for heading/RPM genes and `sail.sail_tracks` for
given waypoint tracks) fill the same per-leg arrays and call `finish`, so GA, baselines and
re-evaluations of old plans compare like with like.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from shiproute_core.flags import FLAG_RTA
from shiproute_core.units import M_PER_NM

from ..geo.landmask import LandMask
from .constraints import leg_flags_and_violation
from .environment import PERF_FIELDS
from .land_walk import LandWalk
from .problem import RouteProblem

LEG_FIELDS = (*PERF_FIELDS, "heading_deg", "rpm", "distance_m", "duration_s", "fuel_t",
              "land_samples", "turn_deg")


@dataclass(frozen=True)
class RouteEvaluation:
    """Evaluated population: nodes (pop, m + 1), legs (pop, m), totals (pop,).

    Node 0 is the departure, node m the arrival. Leg k runs from node k to node k + 1 with
    `legs['heading_deg'][:, k]` steered at `legs['rpm'][:, k]`; NaN-free for active legs.
    """

    lon_deg: np.ndarray  # continuous longitude frame
    lat_deg: np.ndarray
    time_s: np.ndarray  # POSIX s at each node
    legs: dict[str, np.ndarray]
    leg_flags: np.ndarray  # uint32 (pop, m)
    fuel_t: np.ndarray
    distance_m: np.ndarray
    eta_s: np.ndarray
    flags: np.ndarray  # uint32 (pop,), OR of leg flags + FLAG_RTA
    violation: np.ndarray  # >= 0, 0 = feasible
    objective: np.ndarray  # value minimised (t, NM or h by problem.objective)

    @property
    def feasible(self) -> np.ndarray:
        """True where every constraint holds."""
        return self.violation <= 0.0

    def take(self, idx: np.ndarray | int) -> RouteEvaluation:
        """Sub-population (keeps 2-D shapes for a single index)."""
        idx = np.atleast_1d(idx)
        return RouteEvaluation(
            self.lon_deg[idx], self.lat_deg[idx], self.time_s[idx],
            {k: v[idx] for k, v in self.legs.items()}, self.leg_flags[idx], self.fuel_t[idx],
            self.distance_m[idx], self.eta_s[idx], self.flags[idx], self.violation[idx],
            self.objective[idx],
        )


def objective_of(problem: RouteProblem, fuel_t, distance_m, eta_s) -> np.ndarray:
    """Objective value: fuel [t], distance [NM], elapsed time [h], CO2 [t] or cost [USD]."""
    if problem.objective == "distance":
        return distance_m / M_PER_NM
    if problem.objective == "eta":
        return (eta_s - problem.depart_s) / 3600.0
    if problem.objective in ("co2", "cost"):
        hours = (np.asarray(eta_s, dtype=float) - problem.depart_s) / 3600.0
        return (problem.objective_per_t_fuel * np.asarray(fuel_t, dtype=float)
                + problem.objective_per_h * hours)
    return np.asarray(fuel_t, dtype=float)


PILOTAGE_DEPTH_M = 10.0 * M_PER_NM  # depth next to ports/approach ends: dredged channels


def clear_ports(problem: RouteProblem, lon: np.ndarray, lat: np.ndarray,
                 distance_m: np.ndarray, clearance_m: float | None = None
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Leg end points with the first/last `port_clearance_m` (or `clearance_m`) next to a
    port cut off."""
    lon0, lat0 = lon[:, :-1].copy(), lat[:, :-1].copy()
    lon1, lat1 = lon[:, 1:].copy(), lat[:, 1:].copy()
    cut = problem.port_clearance_m if clearance_m is None else clearance_m
    frac = np.clip(cut / np.maximum(distance_m, 1.0), 0.0, 1.0)
    at_dep = (np.abs(lon0 - problem.dep_lon_deg) < 1e-9) & (
        np.abs(lat0 - problem.dep_lat_deg) < 1e-9)
    at_arr = (np.abs(lon1 - problem.arr_lon_deg) < 1e-9) & (
        np.abs(lat1 - problem.arr_lat_deg) < 1e-9)
    f0 = np.where(at_dep, frac, 0.0)
    f1 = np.where(at_arr, frac, 0.0)
    dlon, dlat = lon1 - lon0, lat1 - lat0
    return (lon0 + f0 * dlon, lat0 + f0 * dlat, lon1 - f1 * dlon, lat1 - f1 * dlat)


def finish(
    problem: RouteProblem,
    land: LandMask | None,
    lon: np.ndarray,
    lat: np.ndarray,
    time_s: np.ndarray,
    legs: dict[str, np.ndarray],
    land_samples: np.ndarray | None = None,
) -> RouteEvaluation:
    """Land check, constraint flags, violations, totals and objective of filled legs.

    `land_samples` (pop, m), when given, replaces the land check (the fast evaluator
    computes it with a coarse pre-filter before the same exact segment test)."""
    active = legs["duration_s"] > 0
    if land_samples is not None:
        legs["land_samples"] = np.where(active, land_samples, 0)
    elif land is not None:
        lon0, lat0, lon1, lat1 = clear_ports(problem, lon, lat, legs["distance_m"])
        # the GA's test (`land_walk`): the finest coastline with the problem's clearance
        samples = LandWalk(problem, land, exact_tight=True).segments(lon0, lat0, lon1, lat1)
        legs["land_samples"] = np.where(active, samples, 0)
    else:
        legs["land_samples"] = np.zeros(active.shape, dtype=np.int64)
    under_keel = problem.limits.under_keel
    if under_keel is not None:  # not in the pilotage waters next to ports and approach ends
        ends = clear_ports(problem, lon, lat, legs["distance_m"], PILOTAGE_DEPTH_M)
        depth, ukc = under_keel.leg_clearance(*ends, legs["stw_m_s"], legs["hs_m"])
        legs["min_depth_m"] = np.where(active, depth, np.nan)
        legs["ukc_m"] = np.where(active, ukc, np.nan)
    penalty = 0.0
    zones = problem.limits.zones
    if zones is not None:
        ends = clear_ports(problem, lon, lat, legs["distance_m"])
        share = zones.leg_inside(*ends)  # (zone, pop, m)
        leg_nm = np.where(active, legs["distance_m"], 0.0) / M_PER_NM
        hard = np.array([z.hard for z in zones.zones])
        per_nm = np.array([z.penalty_per_nm for z in zones.zones])
        legs["zone_nm"] = share[hard].sum(axis=0) * leg_nm
        penalty = (np.tensordot(per_nm[~hard], share[~hard], axes=1) * leg_nm).sum(axis=1)
    legs["lat_end_deg"] = lat[:, 1:]
    leg_flags, leg_viol = leg_flags_and_violation(legs, problem.limits, active)
    del legs["lat_end_deg"]
    fuel = legs["fuel_t"].sum(axis=1)
    dist = legs["distance_m"].sum(axis=1)
    eta = time_s[:, -1]
    late_h = np.maximum(0.0, eta - problem.rta_s) / 3600.0
    violation = leg_viol.sum(axis=1) + np.where(late_h > 0, 1.0 + late_h, 0.0)
    flags = np.bitwise_or.reduce(leg_flags, axis=1) | np.where(late_h > 0, FLAG_RTA, 0).astype(
        np.uint32
    )
    violation = np.where(np.isfinite(violation), violation, 1e12)
    return RouteEvaluation(
        lon, lat, time_s, legs, leg_flags, fuel, dist, eta, flags, violation,
        objective_of(problem, fuel, dist, eta) + penalty,
    )
