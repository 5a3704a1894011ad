"""The fast evaluator's `evaluation.finish`: the same RouteEvaluation, bit for bit, with the
per-leg work (port cuts, constraint flags and violations) in compiled kernels.

`finish` builds its answer from some forty whole-array numpy operations per population, a
third of an evaluation's time at GA population sizes. Here the leg terms run in one compiled
pass (`_finish_kernel`); the row totals (fuel, distance, violation) stay numpy reductions so
their summation order, hence every bit, is `finish`'s. Problems with no-go zones take
`finish` itself (their penalty terms are not compiled).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from shiproute_core import flags as fl

from ..chunks import in_chunks
from ..geo.depth_scan import MIN_CHUNK as DEPTH_MIN_CHUNK
from ..geo.depth_scan import capped_scan
from . import _finish_kernel as kf
from .evaluation import PILOTAGE_DEPTH_M, RouteEvaluation, finish, objective_of
from .problem import RouteLimits, RouteProblem

Ends = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]
Work = Callable[[int, int], None]  # work on legs a..b of a flattened population
_BITS = np.array([fl.FLAG_LAND, fl.FLAG_SLAMMING, fl.FLAG_DECK_WETNESS,
                  fl.FLAG_PROPELLER_EMERGENCE, fl.FLAG_HEADING_CHANGE, fl.FLAG_RPM_RANGE,
                  fl.FLAG_WAVE_LIMIT, fl.FLAG_WIND_LIMIT, fl.FLAG_IMO_SURF_RIDING,
                  fl.FLAG_IMO_PARAMETRIC_ROLL, fl.FLAG_IMO_SYNCHRONOUS_ROLL,
                  fl.FLAG_IMO_HIGH_WAVE_GROUP, fl.FLAG_ENGINE_LIMIT, fl.FLAG_DEPTH,
                  fl.FLAG_LATITUDE], dtype=np.uint32)


def port_cut_ends(problem: RouteProblem, lon: np.ndarray, lat: np.ndarray,
                  distance_m: np.ndarray, cut_m: float) -> Ends:
    """`evaluation.clear_ports(problem, lon, lat, distance_m, cut_m)`, compiled."""
    out = tuple(np.empty(distance_m.shape) for _ in range(4))
    kf.port_cut_ends(np.ascontiguousarray(lon), np.ascontiguousarray(lat),
                     np.ascontiguousarray(distance_m), problem.dep_lon_deg, problem.dep_lat_deg,
                     problem.arr_lon_deg, problem.arr_lat_deg, float(cut_m), *out)
    return out[0], out[1], out[2], out[3]


def leg_cuts(problem: RouteProblem) -> tuple[float, ...]:
    """The port cuts [m] `finish_fast` needs leg ends for: the land scan's
    (`port_clearance_m`) and, with a UKC constraint outside no-go zone problems, the depth
    scan's (`PILOTAGE_DEPTH_M`)."""
    if problem.limits.under_keel is None or problem.limits.zones is not None:
        return (problem.port_clearance_m,)
    return (problem.port_clearance_m, PILOTAGE_DEPTH_M)


def _cut(problem: RouteProblem, lon: np.ndarray, lat: np.ndarray, distance_m: np.ndarray,
         cut_m: float, given: dict[float, Ends] | None) -> Ends:
    """Leg ends with `cut_m` cut off at the ports: from `given` when there, else computed."""
    if given is not None and cut_m in given:
        return given[cut_m]
    return port_cut_ends(problem, lon, lat, distance_m, cut_m)


def _limit_vectors(limits: RouteLimits, with_ukc: bool) -> tuple[np.ndarray, np.ndarray]:
    """The kernel's scalar limits and check switches of `limits`."""
    lim = np.zeros(kf.N_LIMITS)
    lim[[kf.L_SLAM, kf.L_WET, kf.L_PROP, kf.L_TURN, kf.L_RPM_MIN, kf.L_RPM_MAX, kf.L_LAT]] = (
        limits.p_slamming_max, limits.p_deck_wetness_max, limits.p_propeller_emergence_max,
        limits.max_heading_change_deg, limits.rpm_min, limits.rpm_max, limits.lat_bound_deg)
    checks = np.zeros(kf.N_CHECKS, dtype=np.bool_)
    if limits.max_hs_m is not None:
        lim[kf.L_HS], checks[kf.C_HS] = limits.max_hs_m, True
    if limits.max_wind_m_s is not None:
        lim[kf.L_WIND], checks[kf.C_WIND] = limits.max_wind_m_s, True
    for key, col in (("surf_riding", kf.C_SURF), ("parametric_roll", kf.C_PARAM),
                     ("synchronous_roll", kf.C_SYNC), ("high_wave_group", kf.C_GROUP)):
        checks[col] = key in limits.imo_checks
    checks[kf.C_ENGINE] = bool(limits.engine_limit)
    checks[kf.C_UKC] = with_ukc
    return lim, checks


def finish_fast(problem: RouteProblem, lon: np.ndarray, lat: np.ndarray, time_s: np.ndarray,
                legs: dict[str, np.ndarray],
                land_samples: Callable[[Ends, Work | None], np.ndarray] | None,
                cut_ends: dict[float, Ends] | None = None) -> RouteEvaluation:
    """`finish(problem, land, lon, lat, time_s, legs, land_samples(ends, None))` where `ends`
    are the legs with `problem.port_clearance_m` cut off at the ports (None: no land check).
    The depth scan is handed to `land_samples` as work to run on the same threads.
    `cut_ends`: leg ends per port cut [m] (`leg_cuts`) the caller has computed already."""
    distance = legs["distance_m"]
    if problem.limits.zones is not None:
        samples = None if land_samples is None else land_samples(
            _cut(problem, lon, lat, distance, problem.port_clearance_m, cut_ends), None)
        return finish(problem, None, lon, lat, time_s, legs, samples)
    active = legs["duration_s"] > 0
    under_keel = problem.limits.under_keel
    depth_scan: Work | None = None
    if under_keel is not None:  # not in the pilotage waters next to ports and approach ends
        # `UnderKeel.leg_clearance` (capped) with its scan run alongside the land scan
        ends = _cut(problem, lon, lat, distance, PILOTAGE_DEPTH_M, cut_ends)
        need = under_keel.required_depth_m(legs["stw_m_s"], legs["hs_m"])
        depth, depth_scan = capped_scan(under_keel.bathymetry, *ends, need)
    if land_samples is None:
        legs["land_samples"] = np.zeros(active.shape, dtype=np.int64)
        if depth_scan is not None:
            in_chunks(depth.size, depth_scan, DEPTH_MIN_CHUNK)
    else:
        ends = _cut(problem, lon, lat, distance, problem.port_clearance_m, cut_ends)
        legs["land_samples"] = np.where(active, land_samples(ends, depth_scan), 0)
    ukc = None
    if under_keel is not None:
        depth = depth.reshape(active.shape)
        legs["min_depth_m"] = np.where(active, depth, np.nan)
        legs["ukc_m"] = ukc = np.where(active, depth - need, np.nan)
    shape = active.shape
    leg_f = np.empty((kf.N_LEG_F, *shape))
    for row, key in ((kf.F_SLAM, "p_slamming"), (kf.F_WET, "p_deck_wetness"),
                     (kf.F_PROP, "p_propeller_emergence"), (kf.F_TURN, "turn_deg"),
                     (kf.F_RPM, "rpm"), (kf.F_HS, "hs_m"), (kf.F_WIND, "wind_speed_m_s")):
        leg_f[row] = legs[key]
    leg_f[kf.F_UKC] = 0.0 if ukc is None else ukc
    leg_f[kf.F_LAT_END] = lat[:, 1:]
    leg_b = np.empty((5, *shape), dtype=np.bool_)
    for row, key in ((kf.B_SURF, "surf_riding"), (kf.B_PARAM, "parametric_roll"),
                     (kf.B_SYNC, "synchronous_roll"), (kf.B_GROUP, "high_wave_group"),
                     (kf.B_ENGINE, "engine_limit_exceeded")):
        leg_b[row] = legs[key]
    lim, checks = _limit_vectors(problem.limits, ukc is not None)
    leg_flags = np.empty(shape, dtype=np.uint32)
    leg_viol = np.empty(shape)
    row_flags = np.empty(shape[0], dtype=np.uint32)
    kf.leg_constraints(np.ascontiguousarray(legs["land_samples"], dtype=np.int64), leg_f,
                       leg_b, active, lim, checks, _BITS, leg_flags, leg_viol, row_flags)
    fuel = legs["fuel_t"].sum(axis=1)
    dist = distance.sum(axis=1)
    eta = time_s[:, -1]
    late_h = np.maximum(0.0, eta - problem.rta_s) / 3600.0
    late = late_h > 0
    violation = leg_viol.sum(axis=1) + np.where(late, 1.0 + late_h, 0.0)
    row_flags[late] |= np.uint32(fl.FLAG_RTA)
    violation = np.where(np.isfinite(violation), violation, 1e12)
    return RouteEvaluation(lon, lat, time_s, legs, leg_flags, fuel, dist, eta, row_flags,
                           violation, objective_of(problem, fuel, dist, eta) + 0.0)
