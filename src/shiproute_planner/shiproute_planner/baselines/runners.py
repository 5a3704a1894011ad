"""Baseline runners: each turns one search method into a plan judged by the planner's evaluator.

Path-only methods (isochrone, Dijkstra, A*) search at the constant RPM that makes the great
circle meet the RTA, then hold the lowest constant RPM that meets the RTA on the path found,
and search again at that RPM if it moved or the route broke a limit (at most three rounds,
keeping the best). Two-stage methods re-time the Dijkstra/A* path
with the DP speed schedule. 3DDP and time-constrained A* choose per-leg RPM themselves.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from ..method_context import baseline_track
from ..route.rta import constant_rpm_for_rta
from ..route.sail import sail_tracks
from .ddp3 import Ddp3Config, ddp3_route
from .errors import NoRouteFoundError
from .great_circle import RTA_FIT_EVALUATIONS
from .grid_search import search_grid, shortest_sea_path
from .inputs import BaselineInputs
from .isochrone import IsochroneConfig, isochrone_route
from .latlon_grid import build_grid
from .paths import limit_turns
from .result import BaselineResult
from .speed_refine import refine_schedule
from .speed_schedule import optimise_schedule
from .tc_astar import tc_astar_route

RPM_REFIT_TOLERANCE = 0.5
PATH_ONLY_ROUNDS = 3
TC_ASTAR_RTA_MARGINS = (0.0, 0.03, 0.06, 0.1, 0.15)  # share of the time window


@dataclass(frozen=True)
class GraphOptions:
    """Resolution of the graph searches (defaults sized for an ocean crossing)."""

    grid_step_deg: float = 0.5
    grid_margin_deg: float = 6.0
    neighbours: int = 16
    isochrone: IsochroneConfig = field(default_factory=IsochroneConfig)
    ddp3: Ddp3Config = field(default_factory=Ddp3Config)
    schedule_levels: int = 17
    schedule_bin_s: float = 1800.0
    schedule_max_leg_nm: float = 120.0
    ddp3_levels: int = 13
    tc_astar_levels: int = 6
    tc_astar_grid_step_deg: float = 1.0


def _gc_rpm(inp: BaselineInputs) -> float:
    _, lon, lat = baseline_track(inp.problem, inp.land)
    rpm, _ = constant_rpm_for_rta(inp.problem, inp.env, None, lon, lat)
    return rpm


def _path_only(inp: BaselineInputs, method: str, search) -> BaselineResult:
    """Search at the great-circle RPM, refit the constant RPM to the RTA, re-search if needed."""
    t0 = time.perf_counter()
    rpm = _gc_rpm(inp)
    legs = route_evals = 0
    best = None
    for _ in range(PATH_ONLY_ROUNDS):
        lon, lat, n_legs = search(rpm)
        lon, lat = _smooth(inp, lon, lat)
        legs += n_legs
        new_rpm, ev = constant_rpm_for_rta(inp.problem, inp.env, inp.land, lon, lat)
        route_evals += RTA_FIT_EVALUATIONS
        if best is None or _worse(best[1], ev):
            best = (new_rpm, ev)
        moved = abs(new_rpm - rpm) > RPM_REFIT_TOLERANCE
        rpm = new_rpm
        if not moved and ev.feasible[0]:
            break
    assert best is not None, "PATH_ONLY_ROUNDS >= 1: one round always runs"
    rpm, ev = best
    return BaselineResult(method, ev, time.perf_counter() - t0, False, route_evals, legs,
                          notes=(f"constant rpm {rpm:.2f}",))


def _smooth(inp: BaselineInputs, lon: np.ndarray, lat: np.ndarray):
    """Path with turns over the heading-change limit pulled straight where the sea allows."""
    s_lon, s_lat, _ = limit_turns(lon, lat, inp.problem.limits.max_heading_change_deg,
                                  inp.sailor().crosses_land)
    return s_lon, s_lat


def _smooth_with_rpm(inp: BaselineInputs, lon: np.ndarray, lat: np.ndarray, rpm: np.ndarray):
    """`_smooth` for a path with one RPM per leg: a merged leg keeps its first part's RPM."""
    s_lon, s_lat, kept = limit_turns(lon, lat, inp.problem.limits.max_heading_change_deg,
                                     inp.sailor().crosses_land)
    return s_lon, s_lat, np.asarray(rpm)[kept[:-1]]


def run_isochrone(inp: BaselineInputs, opts: GraphOptions | None = None) -> BaselineResult:
    o = opts or GraphOptions()
    p = inp.problem
    sailor = inp.sailor()

    def search(rpm: float):
        r = isochrone_route(sailor, p.dep_lon_deg, p.dep_lat_deg, p.arr_lon_deg, p.arr_lat_deg,
                            p.depart_s, rpm, o.isochrone)
        return r.lon_deg, r.lat_deg, r.leg_evaluations

    return _path_only(inp, "isochrone", search)


def _grid(inp: BaselineInputs, o: GraphOptions, step_deg: float):
    p = inp.problem
    return build_grid(inp.sailor(), p.dep_lon_deg, p.dep_lat_deg, p.arr_lon_deg, p.arr_lat_deg,
                      lat_step_deg=step_deg, margin_deg=o.grid_margin_deg,
                      neighbours=o.neighbours, max_abs_lat_deg=p.limits.lat_bound_deg)


def run_grid(inp: BaselineInputs, astar: bool, opts: GraphOptions | None = None) -> BaselineResult:
    """Dijkstra (`astar=False`) or A* on the lat/lon grid, path only, constant RPM."""
    o = opts or GraphOptions()
    grid = _grid(inp, o, o.grid_step_deg)
    sailor = inp.sailor()

    def search(rpm: float):
        g = search_grid(grid, sailor, inp.problem.depart_s, rpm, astar)
        return g.lon_deg, g.lat_deg, g.leg_evaluations

    return _path_only(inp, "astar" if astar else "dijkstra", search)


def run_two_stage(
    inp: BaselineInputs, astar: bool, opts: GraphOptions | None = None
) -> BaselineResult:
    """The Dijkstra/A* path with its RPM schedule re-optimised to meet the RTA (two-stage)."""
    o = opts or GraphOptions()
    t0 = time.perf_counter()
    first = run_grid(inp, astar, o)
    return retime_path(inp, first, ("astar" if astar else "dijkstra") + "_rpm", o, t0)


def retime_path(inp: BaselineInputs, first: BaselineResult, method: str, o: GraphOptions,
                t0: float) -> BaselineResult:
    """Stage two: least-fuel RPM per leg on `first`'s track (legs split to <= max_leg_nm)."""
    from shiproute_core.geodesy import densify_track
    from shiproute_core.units import M_PER_NM

    ev = first.evaluation
    lon, lat = densify_track(ev.lon_deg[0], ev.lat_deg[0], o.schedule_max_leg_nm * M_PER_NM)
    p = inp.problem
    # levels: an even spread plus a fine comb around the path's constant RPM, so the constant
    # schedule of stage one is itself a candidate of stage two
    rpm_c = float(np.median(ev.legs["rpm"][0]))
    comb = rpm_c + np.arange(-6.0, 6.01, 1.0)
    levels = np.unique(np.clip(np.r_[inp.rpm_levels(o.schedule_levels), comb, rpm_c],
                               p.limits.rpm_min, p.limits.rpm_max))
    sched = optimise_schedule(inp.sailor(), lon, lat, p.depart_s, p.rta_s, levels,
                              o.schedule_bin_s)
    dp = sail_tracks(p, inp.env, inp.land, lon[None], lat[None], sched.rpm[None])
    # refine from the better of the DP schedule and the constant RPM of stage one
    const = sail_tracks(p, inp.env, inp.land, lon[None], lat[None], np.full((1, lon.size - 1),
                                                                              rpm_c))
    start, start_ev = (sched.rpm, dp) if not _worse(dp, const) else (
        np.full(lon.size - 1, rpm_c), const)
    _, final, n_ref = refine_schedule(p, inp.env, inp.land, lon, lat, start, p.stage_s)
    notes: tuple[str, ...] = ()
    if _worse(final, start_ev):
        final, notes = start_ev, ("refinement did not improve the DP/constant schedule",)
    return BaselineResult(method, final, time.perf_counter() - t0, leg_rpm_varies(
        final.legs["rpm"][0][final.legs["duration_s"][0] > 0]),
        first.route_evaluations + 3 + n_ref, first.leg_evaluations + sched.leg_evaluations,
        notes=notes)


def _worse(a, b) -> bool:
    """True if evaluation `a` is worse than `b` under feasibility-first rules."""
    va, vb = float(a.violation[0]), float(b.violation[0])
    if (va > 0) != (vb > 0):
        return va > 0
    if va > 0:
        return va > vb
    return float(a.fuel_t[0]) > float(b.fuel_t[0])


def run_ddp3(inp: BaselineInputs, opts: GraphOptions | None = None) -> BaselineResult:
    o = opts or GraphOptions()
    t0 = time.perf_counter()
    p = inp.problem
    ref_lon, ref_lat = reference_line(inp, o)
    r = ddp3_route(inp.sailor(), ref_lon, ref_lat, p.depart_s, p.rta_s,
                   inp.rpm_levels(o.ddp3_levels), o.ddp3)
    lon, lat, rpm = _smooth_with_rpm(inp, r.lon_deg, r.lat_deg, r.rpm)
    final = sail_tracks(p, inp.env, inp.land, lon[None], lat[None], rpm[None])
    return BaselineResult("ddp3", final, time.perf_counter() - t0, True, 1, r.leg_evaluations,
                          pareto_eta_s=r.pareto_eta_s, pareto_fuel_t=r.pareto_fuel_t)


def reference_line(inp: BaselineInputs, o: GraphOptions) -> tuple[np.ndarray, np.ndarray]:
    """Great circle if it stays at sea, else the shortest sea path on the search grid."""
    from ..route.seeding import great_circle_track

    lon, lat = great_circle_track(inp.problem)
    if not inp.sailor().crosses_land(lon[:-1], lat[:-1], lon[1:], lat[1:]).any():
        return lon, lat
    return shortest_sea_path(_grid(inp, o, o.grid_step_deg))


def run_tc_astar(inp: BaselineInputs, opts: GraphOptions | None = None) -> BaselineResult:
    o = opts or GraphOptions()
    t0 = time.perf_counter()
    p = inp.problem
    grid = _grid(inp, o, o.tc_astar_grid_step_deg)
    sailor = inp.sailor()
    levels = inp.rpm_levels(o.tc_astar_levels)
    window = p.rta_s - p.depart_s
    legs = 0
    # The fuel-first search can spend the time window on cheap early legs and then find no
    # way to arrive; like a navigator it then plans against an earlier target time.
    for margin in TC_ASTAR_RTA_MARGINS:
        try:
            r = tc_astar_route(grid, sailor, p.depart_s, p.rta_s - margin * window, levels)
        except NoRouteFoundError:
            legs += sailor.evaluations
            sailor.evaluations = 0
            continue
        lon, lat, rpm = _smooth_with_rpm(inp, r.lon_deg, r.lat_deg, r.rpm)
        final = sail_tracks(p, inp.env, inp.land, lon[None], lat[None], rpm[None])
        if final.eta_s[0] <= p.rta_s or margin == TC_ASTAR_RTA_MARGINS[-1]:
            return BaselineResult(
                "tc_astar", final, time.perf_counter() - t0, True, 1, legs + r.leg_evaluations,
                notes=(f"{r.expansions} ext-node expansions", f"RTA margin {margin:.0%}"))
        legs += r.leg_evaluations
    raise NoRouteFoundError("time-constrained A* found no route even with a 15 % RTA margin")


def leg_rpm_varies(rpm: np.ndarray, tol: float = 1e-6) -> bool:
    """True when a route's active legs use more than one RPM."""
    r = np.asarray(rpm, dtype=float)
    return bool(r.size and np.ptp(r) > tol)
