"""Baseline runners: each turns one search method into a plan judged by the planner's evaluator.

Path-only methods (isochrone, Dijkstra, A*) search at the constant RPM that makes the great
circle meet the RTA, then hold the lowest constant RPM that meets the RTA on the path found,
and search once more at that RPM if it moved. Two-stage methods re-time the Dijkstra/A* path
with the DP speed schedule. 3DDP and time-constrained A* choose per-leg RPM themselves.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from ..route.sail import sail_tracks
from .ddp3 import Ddp3Config, ddp3_route
from .great_circle import great_circle_track
from .grid_search import search_grid
from .inputs import BaselineInputs
from .isochrone import IsochroneConfig, isochrone_route
from .latlon_grid import build_grid
from .result import BaselineResult
from .rpm_fit import constant_rpm_for_rta
from .speed_schedule import optimise_schedule
from .tc_astar import tc_astar_route

RPM_REFIT_TOLERANCE = 0.5


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
    ddp3_levels: int = 9
    tc_astar_levels: int = 6
    tc_astar_grid_step_deg: float = 1.0


def _gc_rpm(inp: BaselineInputs) -> float:
    lon, lat, _ = great_circle_track(inp)
    rpm, _, _ = constant_rpm_for_rta(inp.problem, inp.env, inp.land, lon, lat)
    return rpm


def _path_only(inp: BaselineInputs, method: str, search) -> BaselineResult:
    """Search at the great-circle RPM, refit the constant RPM to the RTA, re-search if needed."""
    t0 = time.perf_counter()
    rpm = _gc_rpm(inp)
    legs = route_evals = 0
    lon = lat = None
    for _ in range(2):
        lon, lat, n_legs = search(rpm)
        legs += n_legs
        new_rpm, ev, n_ev = constant_rpm_for_rta(inp.problem, inp.env, inp.land, lon, lat)
        route_evals += n_ev
        moved = abs(new_rpm - rpm) > RPM_REFIT_TOLERANCE
        rpm = new_rpm
        if not moved:
            break
    return BaselineResult(method, ev, time.perf_counter() - t0, False, route_evals, legs,
                          notes=(f"constant rpm {rpm:.2f}",))


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
    from .geodesy import M_PER_NM, densify_track

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
    final = sail_tracks(p, inp.env, inp.land, lon[None], lat[None], sched.rpm[None])
    notes = ()
    if _worse(final, ev):
        final, notes = ev, ("the DP schedule was not better than the constant RPM; kept it",)
    return BaselineResult(method, final, time.perf_counter() - t0, leg_rpm_varies(
        final.legs["rpm"][0][final.legs["duration_s"][0] > 0]), first.route_evaluations + 1,
        first.leg_evaluations + sched.leg_evaluations, notes=notes)


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
    r = ddp3_route(inp.sailor(), p.dep_lon_deg, p.dep_lat_deg, p.arr_lon_deg, p.arr_lat_deg,
                   p.depart_s, p.rta_s, inp.rpm_levels(o.ddp3_levels), o.ddp3)
    final = sail_tracks(p, inp.env, inp.land, r.lon_deg[None], r.lat_deg[None], r.rpm[None])
    return BaselineResult("ddp3", final, time.perf_counter() - t0, True, 1, r.leg_evaluations,
                          pareto_eta_s=r.pareto_eta_s, pareto_fuel_t=r.pareto_fuel_t)


def run_tc_astar(inp: BaselineInputs, opts: GraphOptions | None = None) -> BaselineResult:
    o = opts or GraphOptions()
    t0 = time.perf_counter()
    p = inp.problem
    grid = _grid(inp, o, o.tc_astar_grid_step_deg)
    r = tc_astar_route(grid, inp.sailor(), p.depart_s, p.rta_s, inp.rpm_levels(o.tc_astar_levels))
    final = sail_tracks(p, inp.env, inp.land, r.lon_deg[None], r.lat_deg[None], r.rpm[None])
    return BaselineResult("tc_astar", final, time.perf_counter() - t0, True, 1, r.leg_evaluations,
                          notes=(f"{r.expansions} ext-node expansions",))


def leg_rpm_varies(rpm: np.ndarray, tol: float = 1e-6) -> bool:
    """True when a route's active legs use more than one RPM."""
    r = np.asarray(rpm, dtype=float)
    return bool(r.size and np.ptp(r) > tol)
