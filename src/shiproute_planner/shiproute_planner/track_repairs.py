"""Repairs of a stale re-plan's route in track space, the ones a navigator tries first when a
new forecast breaks the route ahead: the same track re-timed (faster or slower up to the
broken stretch, the rest of the way at the speed that still makes the arrival time, so the
ship meets the weather there at another time) and the broken stretch moved off to either
side (RPM scaled by the longer track's length). All are converted to genes in one
`track_to_genes` pass: re-timing in gene space would move the nodes along the same headings
(a faster copy overshoots and turns back), which the track keeps."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from shiproute_core.geodesy import direct, inverse

from .route.environment import Environment
from .route.evaluation import RouteEvaluation
from .route.problem import RouteProblem
from .route.seeding import TrackSeed, track_to_genes
from .rpm_factor import TARGET_BEFORE_RTA_S, retimed_rpm

# RPM factor up to the cut; the legs after it get the factor that keeps the arrival time
# (speed ~ RPM), so a copy reaches the broken stretch earlier or later by up to ~10 %
RETIME_FACTORS = (0.91, 0.96, 1.04, 1.09)
# lateral shift of the broken stretch's nodes, in mean leg lengths (half of it on the node
# before and after the stretch), to either side
SHIFTS_LEGS = (0.5, 1.0, 2.0)
REPAIR_ROUNDS = 2  # a round repairs the least broken repair of the round before
# headings tried per stage when the repaired tracks become genes: they follow a track the
# search already sailed, so a narrower fan than a new polyline's does (less than half the
# time)
REPAIR_FAN_DEG = 30.0
REPAIR_FAN_N = 5


def broken_stretch(ev: RouteEvaluation, row: int) -> tuple[int, int] | None:
    """(first broken leg, leg after the last) of route `row`; a late route without a broken
    leg is broken over its whole length (all of it can be sailed faster); None when it is
    not broken at all."""
    bad = np.flatnonzero(ev.leg_flags[row] != 0)
    if bad.size:
        return int(bad.min()), int(bad.max()) + 1
    return (0, ev.leg_flags.shape[1]) if ev.violation[row] > 0 else None


def retimed_tracks(problem: RouteProblem, ev: RouteEvaluation, row: int,
                   stretch: tuple[int, int]) -> list[TrackSeed]:
    """Route `row`'s track with its RPMs scaled by each of RETIME_FACTORS up to the start
    and up to the end of the broken stretch, and after that by the factor that brings it in
    TARGET_BEFORE_RTA_S before the RTA (times scale as 1 / RPM)."""
    lon, lat = ev.lon_deg[row], ev.lat_deg[row]
    rpm = np.asarray(ev.legs["rpm"][row], dtype=float)
    dur = np.asarray(ev.legs["duration_s"][row], dtype=float)
    window_s = problem.rta_s - TARGET_BEFORE_RTA_S - float(ev.time_s[row, 0])
    out = []
    for cut in sorted({max(stretch[0], 1), stretch[1]}):
        if cut >= dur.size:
            continue
        for f in RETIME_FACTORS:
            r = retimed_rpm(rpm, dur, cut, window_s, f)
            if r is not None:
                out.append(TrackSeed("previous_plan_retimed", lon, lat, r))
    return out


def shifted_tracks(ev: RouteEvaluation, row: int, stretch: tuple[int, int]) -> list[TrackSeed]:
    """Route `row`'s track with the nodes of the broken stretch moved sideways by
    SHIFTS_LEGS mean leg lengths (half as far on the nodes either side), to port and to
    starboard, RPMs scaled by the new length over the old (speed ~ RPM)."""
    lon, lat = np.asarray(ev.lon_deg[row], dtype=float), np.asarray(ev.lat_deg[row], dtype=float)
    m = lon.size - 1
    rpm = np.asarray(ev.legs["rpm"][row], dtype=float)
    _, dist = inverse(lon[:-1], lat[:-1], lon[1:], lat[1:])
    dist = np.atleast_1d(np.asarray(dist, dtype=float))
    length = float(dist.sum())
    active = dist[dist > 0]
    if m < 2 or active.size == 0:
        return []
    leg_m = float(active.mean())
    nodes = np.arange(max(stretch[0] - 1, 1), min(stretch[1] + 1, m - 1) + 1)
    weight = np.where((nodes >= stretch[0]) & (nodes <= stretch[1]), 1.0, 0.5)
    course, _ = inverse(lon[nodes - 1], lat[nodes - 1], lon[nodes + 1], lat[nodes + 1])
    out = []
    for shift in SHIFTS_LEGS:
        for side in (-90.0, 90.0):
            s_lon, s_lat = lon.copy(), lat.copy()
            s_lon[nodes], s_lat[nodes] = direct(lon[nodes], lat[nodes], course + side,
                                                weight * shift * leg_m)
            _, d = inverse(s_lon[:-1], s_lat[:-1], s_lon[1:], s_lat[1:])
            scale = float(np.sum(d)) / max(length, 1.0)
            out.append(TrackSeed("previous_plan_shifted", s_lon, s_lat, rpm * scale))
    return out


def track_repairs(problem: RouteProblem, env: Environment, land: Any, fast: Any,
                  ev: RouteEvaluation, row: int,
                  evaluate: Callable[[np.ndarray], RouteEvaluation],
                  spent: Callable[[], bool] = lambda: False,
                  overrun: Callable[[], bool] = lambda: False
                  ) -> tuple[np.ndarray, list[str], bool]:
    """Genes and source names of route `row` re-timed and shifted round its broken stretch
    (none when it is not broken), and whether one of them is feasible; while none of a
    round's repairs is, the least broken of them is repaired in turn (a storm too wide for
    one shift, a lateness the shift added), up to REPAIR_ROUNDS rounds and only while
    `spent()` (the seeding phase's share of the budget) says there is time. The first
    round always runs (a stale re-plan without repairs rarely ends feasible), with only the
    re-timed tracks when the share is spent already, unless `overrun()` says the seeding
    stalled far past its share."""
    genes, names, feasible = [], [], False
    for round_no in range(REPAIR_ROUNDS):
        short = spent()
        if short and (round_no > 0 or overrun()):
            break
        stretch = broken_stretch(ev, row)
        if stretch is None:
            break
        seeds = retimed_tracks(problem, ev, row, stretch) + (
            [] if short else shifted_tracks(ev, row, stretch))
        if not seeds:
            break
        x = track_to_genes(problem, env, seeds, land, fan_deg=REPAIR_FAN_DEG,
                           fan_n=REPAIR_FAN_N, fast=fast)
        genes.append(x)
        names += [s.source for s in seeds]
        ev = evaluate(x)
        feasible = bool((ev.violation <= 0.0).any())
        if feasible:
            break
        row = int(np.argmin(ev.violation))
    if not genes:
        return np.empty((0, problem.n_var)), [], False
    return np.concatenate(genes), names, feasible
