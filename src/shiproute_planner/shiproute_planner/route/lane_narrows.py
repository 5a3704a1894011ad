"""Narrows found by the sea lane's repair: water the room raster reads as open sea where no
route keeps the open-sea clearance.

The room raster (`geo.narrow_water`) sorts water by the largest level-0 distance within
10 NM, so a channel narrower than twice the open-sea clearance that opens into wide water
within 10 NM (Pentland Firth between the Orkneys and Caithness, the Sunda Strait by
Sangiang) reads as open sea, and a search keeping the open-sea clearance there finds every
route through it infeasible. The lane's full-resolution repair (`route.seed_repair`) already
tries detours keeping the clearance in corridors up to 30 NM wide; where none exists it
falls back to less. The points of the repaired lane still closer to land than the open-sea
clearance, outside the approach zones, are those narrows: the search then keeps the approach
clearance within `clearance.NARROWS_REACH_NM` of them, as in narrow water it finds itself,
and the plan names them.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
from shiproute_core.geodesy import densify_track, distance_within_m
from shiproute_core.units import M_PER_NM

from .problem import RouteProblem

STEP_NM = 0.25  # samples along the repaired lane (as the route check's)
THIN_NM = 2.0  # one narrows point per this much lane: the reach round each covers the gaps
ROUND_DIGITS = 4  # points rounded to 1e-4 deg: a re-plan's rule (its cache keys) repeats


def lane_narrows(problem: RouteProblem, lon: np.ndarray, lat: np.ndarray
                 ) -> tuple[tuple[float, float], ...]:
    """(lon, lat) [deg] of the repaired lane's points (`lon`, `lat`) that the open-sea
    clearance of `problem`'s rule applies to and that keep less than it, off land, outside
    the port clearance round the span's ends; thinned to one per `THIN_NM`."""
    from .seed_repair import rule_need, rule_test, without_narrows

    base = without_narrows(problem)
    rule = base.limits.clearance
    if rule.open_sea_nm <= rule.approach_nm or len(lon) < 2:
        return ()
    d_lon, d_lat = (np.asarray(a, dtype=float) for a in densify_track(
        np.unwrap(np.asarray(lon, dtype=float), period=360.0), np.asarray(lat, dtype=float),
        STEP_NM * M_PER_NM))
    need = rule_need(base)(d_lon, d_lat)
    open_sea = need >= rule.open_sea_nm
    if not open_sea.any():
        return ()
    short = np.zeros(d_lon.size, dtype=bool)
    short[open_sea] = rule_test(base)(d_lon[open_sea], d_lat[open_sea])
    far = problem.port_clearance_m
    for e_lon, e_lat in ((base.dep_lon_deg, base.dep_lat_deg),
                         (base.arr_lon_deg, base.arr_lat_deg)):
        short &= distance_within_m(d_lon, d_lat, e_lon, e_lat, far) >= far
    if short.any():
        from ..geo.full_land import final_land

        idx = np.flatnonzero(short)
        short[idx] = ~np.asarray(final_land().contains(d_lon[idx], d_lat[idx]), dtype=bool)
    out: list[tuple[float, float]] = []
    last = -math.inf
    for k in np.flatnonzero(short):
        if (k - last) * STEP_NM >= THIN_NM:
            lo = ((float(d_lon[k]) + 180.0) % 360.0) - 180.0
            out.append((round(lo, ROUND_DIGITS), round(float(d_lat[k]), ROUND_DIGITS)))
            last = float(k)
    return tuple(out)


def with_narrows(problem: RouteProblem, narrows: tuple[tuple[float, float], ...]
                 ) -> RouteProblem:
    """The problem whose clearance rule keeps the approach clearance round `narrows`."""
    if not narrows:
        return problem
    limits = problem.limits
    return dataclasses.replace(problem, limits=dataclasses.replace(
        limits, clearance=dataclasses.replace(limits.clearance, narrows=tuple(narrows))))


def narrows_statement(narrows: tuple[tuple[float, float], ...], a: str, b: str,
                      open_sea_nm: float, approach_nm: float, reach_nm: float) -> str:
    """The plan's word on the narrows a leg's search relaxed its open-sea clearance in."""
    lon, lat = narrows[0]
    return (f"clearance: the sea lane {a} -> {b} passes water narrower than twice the "
            f"{open_sea_nm:g}-NM open-sea clearance that no detour rounds ({len(narrows)} "
            f"point(s), first at {lat:.3f}N {lon:.3f}E, found by the lane's full-resolution "
            f"repair); within {reach_nm:g} NM of them the search keeps the {approach_nm:g}-NM "
            f"narrow-water clearance")
