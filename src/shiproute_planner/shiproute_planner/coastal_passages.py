"""Port approaches made sailable: the lane-cut approach is replaced by a passage computed on
a fine navigable-water grid (`route.passages`) between the same ends, and the plan says how
it was made (grid, land data, clearance kept, depth) or why the lane was kept.

Passages depend on the lane, the rules and the land and depth data only, so they are kept per
process and in the data directory (a re-plan from the same berth, a later process on the
same machine, pays nothing; a first computation costs ~0.5-3 s plus, once per process,
loading the full-resolution coastline).
"""

from __future__ import annotations

import dataclasses
import hashlib
import os
import time

import numpy as np
from shiproute_core.geodesy import M_PER_NM, inverse

from shiproute_planner.route.approach import Approach

from .errors import PlannerError
from .geo.datadir import data_dir
from .one_off_work import PASSAGES
from .route.passages import (
    FINEST_MAX_CELLS,
    Passage,
    PassageRules,
    best_land_name,
    best_land_resolution,
    compute_passage,
    passage_length_nm,
)

PASSAGE_CACHE_VERSION = 13
SQUAT_SPEED_KN = 12.0  # speed whose squat the passage's depth limit includes
_MEMO: dict[str, Passage | None] = {}
SEA_END_MOVED_NM = 0.01  # a passage ending farther than this from its lane's end says so


# a port approach with no way through 10-30 NM round its lane tries this corridor: the lane's
# first hop may cross a peninsula (Lae: 52 NM of the Huon Peninsula)
APPROACH_WIDEST_CORRIDOR_NM = 80.0


# a port approach whose lane ends in a harbour basin no way reaches (Peterhead's, 1.2 NM
# across its breakwaters) ends in the nearest water the port reaches within this
APPROACH_END_REACH_NM = 5.0


def passage_rules(under_keel) -> PassageRules:
    """Default rules with the depth limit of a ship (`UnderKeel` or None)."""
    if under_keel is None:
        return PassageRules()
    need = float(under_keel.required_depth_m(np.array([SQUAT_SPEED_KN * M_PER_NM / 3600.0]),
                                             np.array([0.0]))[0])
    return PassageRules(required_depth_m=need, bathymetry=under_keel.bathymetry)


def approach_rules(under_keel) -> PassageRules:
    """A port approach's rules: `passage_rules` with the widest corridor as a last resort."""
    return dataclasses.replace(passage_rules(under_keel),
                               widest_corridor_nm=APPROACH_WIDEST_CORRIDOR_NM,
                               end_reach_nm=APPROACH_END_REACH_NM)


def _key(lon: np.ndarray, lat: np.ndarray, rules: PassageRules) -> str:
    h = hashlib.sha1()
    h.update(np.round(np.asarray(lon, dtype=float), 6).tobytes())
    h.update(np.round(np.asarray(lat, dtype=float), 6).tobytes())
    bathy = getattr(rules.bathymetry, "description", "")
    h.update(repr((PASSAGE_CACHE_VERSION, best_land_resolution(),
                   dataclasses.replace(rules, bathymetry=None), bathy)).encode())
    return h.hexdigest()[:20]


def cached_passage(lon: np.ndarray, lat: np.ndarray, rules: PassageRules) -> Passage | None:
    """`compute_passage` through the process memo and the data directory's cache."""
    key = _key(lon, lat, rules)
    if key in _MEMO:
        return _MEMO[key]
    folder = data_dir() / "passages"
    path = folder / f"{key}.npz"
    p: Passage | None = None
    try:
        with np.load(path) as z:
            p = (Passage(z["lon"], z["lat"], float(z["c"]), bool(z["d"]), float(z["w"]),
                         float(z["cell"]))
                 if z["lon"].size else None)
        _MEMO[key] = p
        return p
    except (OSError, ValueError, KeyError):
        pass
    t0 = time.perf_counter()
    p = compute_passage(lon, lat, rules)
    PASSAGES.add(time.perf_counter() - t0)
    _MEMO[key] = p
    try:
        folder.mkdir(parents=True, exist_ok=True)
        tmp = folder / f"{key}.{os.getpid()}.tmp.npz"
        empty = np.zeros(0)
        np.savez(tmp, lon=p.lon_deg if p else empty, lat=p.lat_deg if p else empty,
                 c=p.clearance_nm if p else 0.0, d=p.depth_limited if p else False,
                 w=p.corridor_nm if p else 0.0, cell=p.cell_nm if p else 0.0)
        os.replace(tmp, path)
    except OSError:
        pass  # read-only data directory: kept in memory only
    return p


def computed_approach(ap: Approach | None, port_name: str, arrival: bool,
                      rules: PassageRules) -> tuple[Approach | None, list[str]]:
    """The approach between the same ends computed on the navigable-water grid (arrival
    approaches run sea -> port) and notes for the plan when it deviates from the rules or
    the lane had to be kept. An approach run on past a shoal (`route.approach_shoals`)
    whose passage finds no way round it in water deep enough gives way to its fallback:
    a passage over the shoal would hide it from the optimiser's depth constraint."""
    if ap is None or ap.lon_deg.size < 2:
        return ap, list(ap.notes) if ap is not None else []
    lon, lat = (ap.lon_deg[::-1], ap.lat_deg[::-1]) if arrival else (ap.lon_deg, ap.lat_deg)
    where = f"{'arrival at' if arrival else 'departure from'} {port_name}"
    try:
        p = cached_passage(lon, lat, rules)
    except (OSError, ValueError, MemoryError, PlannerError) as exc:  # the lane, said aloud
        p, failed = None, [f"coastal passage ({where}) not computed ({exc}); the sea lane's "
                           "own geometry is sailed, not land-checked before the route check"]
    else:
        failed = [f"coastal passage ({where}): no way through navigable water at "
                  f"{rules.fine_cell_nm:g} NM resolution (nor at {rules.finest_cell_nm:g} NM, "
                  f"tried on corridors of at most {FINEST_MAX_CELLS:,} cells) within "
                  f"{max(*rules.corridors_nm, rules.widest_corridor_nm):g} NM of the sea "
                  "lane; the lane's own geometry is sailed (see the route check)"]
    if ap.fallback is not None and (p is None or not _keeps_depth(p, rules)):
        back, said = computed_approach(ap.fallback, port_name, arrival, rules)
        return back, [f"coastal passage ({where}): no way round the shallow water next to "
                      f"the port in water of {rules.required_depth_m:.1f} m per the depth "
                      f"grid: it ends {approach_nm(back):.0f} NM from the port, and the "
                      "optimiser's depth constraint decides beyond the first leg's pilotage "
                      "waters", *said]
    if p is None:
        return ap, [*ap.notes, *failed]
    notes = list(ap.notes)
    if p.clearance_nm < rules.clearances_nm[0]:
        notes.append(f"coastal passage ({where}): too narrow for {rules.clearances_nm[0]:g} NM "
                     f"clearance; keeps >= {p.clearance_nm:g} NM from land")
    if not _keeps_depth(p, rules):
        notes.append(f"coastal passage ({where}): no way through water of "
                     f"{rules.required_depth_m:.1f} m (draft, squat at {SQUAT_SPEED_KN:g} kn, "
                     "margin) per the depth grid; passage computed on land and clearance only")
    if p.cell_nm < rules.cell_nm - 1e-9:
        notes.append(f"coastal passage ({where}): computed on {p.cell_nm:.2g} NM cells (narrow "
                     "water)")
    if p.corridor_nm > rules.corridors_nm[0]:
        notes.append(f"coastal passage ({where}): found only {p.corridor_nm:g} NM off the sea "
                     "lane")
    moved_nm = float(inverse(lon[-1], lat[-1], p.lon_deg[-1], p.lat_deg[-1])[1]) / M_PER_NM
    if moved_nm > SEA_END_MOVED_NM:
        notes.append(f"coastal passage ({where}): the sea lane's point where it ends "
                     f"({lat[-1]:.3f}, {lon[-1]:.3f}) is reached from the port only across "
                     f"land ({best_land_name()}: on land, or in a basin behind breakwaters); "
                     f"the passage ends {moved_nm:.2f} NM from it in navigable water, where "
                     f"the {'search ends' if arrival else 'search starts'}")
    lon_p, lat_p = (p.lon_deg[::-1], p.lat_deg[::-1]) if arrival else (p.lon_deg, p.lat_deg)
    return Approach(np.asarray(lon_p, dtype=float), np.asarray(lat_p, dtype=float)), notes


def _keeps_depth(p: Passage, rules: PassageRules) -> bool:
    """True when passage `p` keeps the ship's depth limit, or there is none to keep."""
    return p.depth_limited or rules.required_depth_m is None


def passages_note(rules: PassageRules) -> str:
    """What every computed passage was made with (one line for the plan's warnings)."""
    depth = ("no depth limit (depth not checked)" if rules.required_depth_m is None else
             f"cells shallower than {rules.required_depth_m:.1f} m blocked beyond "
             f"{rules.pilotage_nm:g} NM of the port; a coarse grid's depth (> 1 arc-minute) "
             "counts only 1.5 of its cells or more off the full-resolution coast, nearer the "
             "coastline decides")
    return (f"coastal passages computed on a {rules.cell_nm:g} NM navigable-water grid "
            f"({best_land_name()} land) within {rules.corridors_nm[0]:g} NM of the sea "
            f"lane, keeping >= {rules.clearances_nm[0]:g} NM from land where the water allows "
            f"(inside {rules.berth_nm:g} NM of the berth only land blocks); {depth}")


def approach_nm(ap: Approach | None) -> float:
    """Length [NM] of an approach (0 for none)."""
    return 0.0 if ap is None else passage_length_nm(ap.lon_deg, ap.lat_deg)
