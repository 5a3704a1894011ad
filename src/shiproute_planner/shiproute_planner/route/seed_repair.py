"""Seed tracks repaired at full resolution before the search starts.

The sea lane (`searoute`'s network, resampled to two points per stage) cuts headlands, narrow
passages such as the Kanmon Strait and the clearance round islands: on the search's
full-resolution test a seed and a baseline on it break the rule, and a route round a whole
island ranks before them. Each stretch of such a track with points on full-resolution land
or closer than the clearance rule asks (`route.clearance`, the search's: off land only in
tight water), across the lane's nodes (a node within the clearance moves), gets a local
detour (`route.land_repair.repaired_stretches`: fine navigable grid on which each cell keeps
the clearance the rule asks of its own water, so a detour through a strait keeps the
open-sea clearance once past it), so the baseline and the seeds made from it start clean;
where no detour keeps the clearance, one off land at least (the search penalises the rest).
"""

from __future__ import annotations

import dataclasses
import hashlib
import time
from collections.abc import Callable

import numpy as np
from shiproute_core.geodesy import distance_within_m
from shiproute_core.units import M_PER_NM

from ..one_off_work import LANE_REPAIRS
from .clearance import needed_clearance_nm
from .land_repair import RepairRules, repaired_stretches
from .problem import RouteProblem

SEED_REPAIR_VERSION = 6  # in the cache key: bump when the repair changes
# stretches each side of a break and corridors round it [NM], tried in turn: the widest lets
# a detour round an island whose channel is narrower than twice the open-sea clearance (an
# island ~15 NM across off a coast) keep the rule instead of relaxing it in the channel
WINDOWS_NM = (4.0, 12.0, 30.0)
LEVEL1_SLACK_NM = 0.7  # level 1's looseness (a fine diagonal, the coastline band, one step)




def without_narrows(problem: RouteProblem) -> RouteProblem:
    """The problem under the user's clearance rule (no narrows found by a lane's repair)."""
    limits = problem.limits
    if not limits.clearance.narrows:
        return problem
    return dataclasses.replace(problem, limits=dataclasses.replace(
        limits, clearance=limits.clearance.without_narrows()))


def repair_builds() -> tuple[int, float]:
    """(repairs, seconds) this process has computed rather than read back: one-off work a
    plan's clock does not charge to its search (a re-plan from a new position repairs its
    lane afresh)."""
    return LANE_REPAIRS.totals()


def rule_need(problem: RouteProblem) -> Callable[[np.ndarray, np.ndarray], np.ndarray]:
    """Clearance [NM] the search's rule asks of points (`route.clearance.needed_clearance_nm`:
    by their distance to the nearer span end and the room of their water; 0 off land only)."""
    from ..geo.narrow_water import UNIT_NM as ROOM_UNIT_NM
    from ..geo.narrow_water import default_room

    room = default_room()
    rule = problem.limits.clearance
    cell = 180.0 / room.shape[0]
    within_m = max(rule.free_radius_nm, rule.approach_zone_nm) * M_PER_NM
    ends = [(problem.dep_lon_deg, problem.dep_lat_deg),
            (problem.arr_lon_deg, problem.arr_lat_deg)]

    def need(lon: np.ndarray, lat: np.ndarray) -> np.ndarray:
        lon, lat = np.asarray(lon, dtype=float), np.asarray(lat, dtype=float)
        if rule.open_sea_nm == 0.0 and rule.approach_nm == 0.0:
            return np.zeros(lon.shape)
        # only the zone's edges matter: exact within them, a haversine beyond
        end_nm = np.min([distance_within_m(lon, lat, e[0], e[1], within_m) / M_PER_NM
                         for e in ends], axis=0)
        i = np.clip(((lat + 90.0) // cell).astype(np.int64), 0, room.shape[0] - 1)
        j = np.clip((((lon + 180.0) % 360.0) // cell).astype(np.int64), 0, room.shape[1] - 1)
        return needed_clearance_nm(rule, end_nm, room[i, j] * ROOM_UNIT_NM)

    return need


def rule_test(problem: RouteProblem) -> Callable[[np.ndarray, np.ndarray], np.ndarray]:
    """Point test of the search's rule: True where a point is on full-resolution land or
    closer to it than the problem's clearance rule asks (level-1 lower bound distances)."""
    from ..geo.fine_distance import default_fine_distance
    from ..geo.full_land import final_land

    land, fine, need_nm = final_land(), default_fine_distance(), rule_need(problem)

    def breaks(lon: np.ndarray, lat: np.ndarray) -> np.ndarray:
        lon, lat = np.asarray(lon, dtype=float), np.asarray(lat, dtype=float)
        out = np.asarray(land.contains(lon, lat), dtype=bool)
        need = need_nm(lon, lat)
        near = need > 0.0
        if near.any():
            out[near] |= fine.distance_nm(lon[near], lat[near]) < need[near]
        return out

    return breaks


def repaired_seed_track(problem: RouteProblem, lon: np.ndarray, lat: np.ndarray
                        ) -> tuple[np.ndarray, np.ndarray, int]:
    """(lon, lat, stretches left unrepaired) of a seed track with the stretches that break
    the search's rule detoured (outside the problem's port clearance round both ends); kept
    in the data directory (`seedrepairs/`), so a machine repairs each lane once per rule, as
    it computes each coastal passage once."""
    from ..geo.datadir import data_dir, save_npz_atomic
    from .passages import best_land_resolution

    problem = without_narrows(problem)  # a lane is repaired under the user's rule
    rule = problem.limits.clearance
    under_keel = problem.limits.under_keel
    depth = (None if under_keel is None else float(under_keel.required_depth_m(
        np.array([7.0]), np.array([0.0]))[0]))
    h = hashlib.sha1()
    h.update(np.round(np.asarray(lon, dtype=float), 6).tobytes())
    h.update(np.round(np.asarray(lat, dtype=float), 6).tobytes())
    h.update(repr((SEED_REPAIR_VERSION, best_land_resolution(), rule,
                   problem.port_clearance_m, depth,
                   getattr(getattr(under_keel, "bathymetry", None), "description", ""))
                  ).encode())
    path = data_dir() / "seedrepairs" / f"{h.hexdigest()[:20]}.npz"
    try:
        with np.load(path) as z:
            return z["lon"], z["lat"], int(z["left"])
    except (OSError, ValueError, KeyError):
        pass
    t0 = time.perf_counter()
    out_lon, out_lat, left = _repaired(problem, lon, lat)
    LANE_REPAIRS.add(time.perf_counter() - t0)
    path.parent.mkdir(parents=True, exist_ok=True)
    save_npz_atomic(path, lon=out_lon, lat=out_lat, left=np.array(left))
    return out_lon, out_lat, left


def _repaired(problem: RouteProblem, lon: np.ndarray, lat: np.ndarray
              ) -> tuple[np.ndarray, np.ndarray, int]:
    """`repaired_seed_track` computed."""
    from ..coastal_passages import passage_rules
    from .passages import best_land_polygons

    rule = problem.limits.clearance
    rules = RepairRules()
    # the walk reads level 1, a lower bound up to ~0.7 NM below the true distance: the
    # detours aim that much wider first
    keep = {c + LEVEL1_SLACK_NM for c in (rule.open_sea_nm, rule.approach_nm) if c > 0.0}
    need_nm = rule_need(problem)

    def wider_need_nm(lon: np.ndarray, lat: np.ndarray) -> np.ndarray:
        need = need_nm(lon, lat)
        return np.where(need > 0.0, need + LEVEL1_SLACK_NM, 0.0)

    # each part of a detour keeps the clearance its own water asks (open sea, approach,
    # narrow or tight water), the largest capped first where it cannot
    rules = dataclasses.replace(rules, clearances_nm=tuple(sorted(
        {*keep, *rules.clearances_nm}, reverse=True)), need_nm=wider_need_nm,
        windows_nm=WINDOWS_NM, corridors_nm=WINDOWS_NM)
    from ..geo.full_land import final_land

    polygons, base, skip = (best_land_polygons(), passage_rules(problem.limits.under_keel),
                            problem.port_clearance_m)
    lon, lat, left = repaired_stretches(lon, lat, rule_test(problem), polygons, base, rules,
                                        skip, skip)
    if left:  # no detour keeps the clearance: off land at least (the search penalises the rest)
        lon, lat, left = repaired_stretches(lon, lat, final_land().contains, polygons, base,
                                            rules, skip, skip)
    return lon, lat, left
