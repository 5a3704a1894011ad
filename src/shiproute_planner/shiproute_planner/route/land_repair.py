"""Local detours round land a finished track touches at the final (full-resolution) check.

A leg is sampled where the route check samples it (geodesic points every `CHECK_STEP_M`,
0.25 NM); where samples fall on land, the stretch from `window_nm` before the first land
sample to `window_nm` after the last one is replaced by the shortest path round the obstacle
on a fine navigable-water grid (`route.passages.compute_passage`: full-resolution land,
corridor of `corridor_nm` round the stretch, `clearance_nm` kept from land where there is
room, relaxed step by step where there is not). The detour is kept only when the whole new
leg passes the same dense check; a wider window and corridor are tried next. A leg keeps its
RPM: the caller sails the sub-legs at it and re-evaluates the route.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from shiproute_core.geodesy import densify_track, inverse
from shiproute_core.units import M_PER_NM

from ..geo.nav_grid import land_in_box
from .passages import PassageRules, compute_passage, passage_length_nm
from .track_samples import track_samples

LandTest = Callable[[np.ndarray, np.ndarray], np.ndarray]
#: dense sample spacing (0.25 NM), the route check's own (`route_check.CHECK_STEP_M`)
STEP_M = M_PER_NM / 4.0


@dataclass(frozen=True)
class RepairRules:
    """How detours are made: the stretch replaced each side of the land (`windows_nm`, tried
    in turn with `corridors_nm`), the clearances kept from land where there is room (first
    one preferred, each capping `need_nm` where that is given) and the grid cell."""

    windows_nm: tuple[float, ...] = (4.0, 12.0)
    corridors_nm: tuple[float, ...] = (4.0, 12.0)
    clearances_nm: tuple[float, ...] = (0.5, 0.25, 0.1, 0.0)
    cell_nm: float = 0.1
    need_nm: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = field(
        default=None, compare=False)  # clearance [NM] each point needs (lon, lat)


@dataclass(frozen=True)
class LegRepair:
    """One repaired leg: its new nodes (start and end as before) and what it cost."""

    leg: int
    lon_deg: np.ndarray  # nodes of the new sub-legs, first and last = the old leg's ends
    lat_deg: np.ndarray
    land_lat_deg: float  # first land sample of the old leg
    land_lon_deg: float
    extra_nm: float
    clearance_nm: float

    def row(self, part: str) -> dict:
        """The repair as a JSON-able row of the plan (`part`: which leg of the voyage)."""
        return {"part": part, "stage": self.leg + 1, "land_lat_deg": round(self.land_lat_deg, 4),
                "land_lon_deg": round(self.land_lon_deg, 4),
                "waypoints_added": int(self.lon_deg.size - 2),
                "extra_nm": round(self.extra_nm, 3), "clearance_nm": self.clearance_nm,
                "text": f"land repair ({part}): stage {self.leg + 1} touched land at "
                        f"{self.land_lat_deg:.3f}N {self.land_lon_deg:.3f}E; detour of "
                        f"{self.lon_deg.size - 2} waypoint(s), +{self.extra_nm:.2f} NM, "
                        f"{self.clearance_nm:g} NM off land"}


def leg_samples(lon: np.ndarray, lat: np.ndarray, k: int, skip_start_m: float,
                skip_end_m: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(lon, lat, distance along the leg [m], tested?) of leg `k`'s dense samples; samples
    within `skip_start_m` of the track's start or `skip_end_m` of its end are not tested."""
    plon, plat = densify_track(lon[k:k + 2], lat[k:k + 2], STEP_M)
    plon, plat = np.asarray(plon, dtype=float), np.asarray(plat, dtype=float)
    plon = lon[k] + (plon - lon[k] + 180.0) % 360.0 - 180.0  # the track's longitude frame
    _, d = inverse(plon[:-1], plat[:-1], plon[1:], plat[1:])
    along = np.concatenate([[0.0], np.cumsum(np.atleast_1d(d))])
    _, legs = inverse(lon[:-1], lat[:-1], lon[1:], lat[1:])
    legs = np.atleast_1d(np.asarray(legs, dtype=float))
    before, total = float(legs[:k].sum()), float(legs.sum())
    tested = (before + along >= skip_start_m) & (before + along <= total - skip_end_m)
    return plon, plat, along, tested


def land_legs(lon: np.ndarray, lat: np.ndarray, contains: LandTest, skip_start_m: float = 0.0,
              skip_end_m: float = 0.0, skip_legs: frozenset[int] = frozenset()) -> list[int]:
    """Legs of a track with a tested dense sample on land: the samples of `leg_samples`
    (each leg's start node and its points every STEP_M), all legs in one geodesic pass and
    one land test instead of a pass per leg."""
    m = lon.size - 1
    if m < 1:
        return []
    _, dist = inverse(lon[:-1], lat[:-1], lon[1:], lat[1:])
    dist = np.atleast_1d(np.asarray(dist, dtype=float))
    plon, plat, start, n, along = track_samples(lon, lat, dist, STEP_M)
    tested = (along >= skip_start_m) & (along <= float(dist.sum()) - skip_end_m)
    hit = np.zeros(plon.size, dtype=np.int64)
    if tested.any():
        hit[tested] = np.asarray(contains(plon[tested], plat[tested]), dtype=bool)
    count = np.concatenate([[0], np.cumsum(hit)])
    on_land = count[start + n + 1] - count[start] > 0  # start node and points of each leg
    return [k for k in np.flatnonzero(on_land).tolist() if k not in skip_legs]


def _stretch(plon: np.ndarray, plat: np.ndarray, along: np.ndarray, a_m: float, b_m: float
             ) -> tuple[np.ndarray, np.ndarray]:
    """Dense samples of the leg between `a_m` and `b_m` along it (ends included)."""
    keep = (along >= a_m) & (along <= b_m)
    ia, ib = int(np.argmax(keep)), int(len(keep) - 1 - np.argmax(keep[::-1]))
    return plon[ia:ib + 1], plat[ia:ib + 1]


def repair_leg(lon: np.ndarray, lat: np.ndarray, k: int, contains: LandTest, polygons,
               base: PassageRules, rules: RepairRules = RepairRules(),
               skip_start_m: float = 0.0, skip_end_m: float = 0.0) -> LegRepair | None:
    """A detour for leg `k` of a track (continuous longitudes) round the land its tested
    samples hit, or None when none passes the dense check (or the leg is clean)."""
    plon, plat, along, tested = leg_samples(lon, lat, k, skip_start_m, skip_end_m)
    hit = np.zeros(plon.size, dtype=bool)
    hit[tested] = np.asarray(contains(plon[tested], plat[tested]), dtype=bool)
    if not hit.any():
        return None
    first, last = int(np.argmax(hit)), int(hit.size - 1 - np.argmax(hit[::-1]))
    old_nm = float(along[-1]) / M_PER_NM
    for window_nm, corridor_nm in zip(rules.windows_nm, rules.corridors_nm, strict=True):
        a_m = max(float(along[first]) - window_nm * M_PER_NM, 0.0)
        b_m = min(float(along[last]) + window_nm * M_PER_NM, float(along[-1]))
        s_lon, s_lat = _stretch(plon, plat, along, a_m, b_m)
        step = max(1, round(0.5 * M_PER_NM / STEP_M))  # guide points every ~0.5 NM
        guide_lon = np.concatenate([s_lon[:-1:step], s_lon[-1:]])
        guide_lat = np.concatenate([s_lat[:-1:step], s_lat[-1:]])
        passage_rules = dataclasses.replace(
            base, clearances_nm=rules.clearances_nm, cell_nm=rules.cell_nm,
            fine_cell_nm=rules.cell_nm / 2.0, corridors_nm=(corridor_nm,), berth_nm=0.0,
            pilotage_nm=0.0, prefer_off_nm=2.0 * rules.clearances_nm[0],
            need_nm=rules.need_nm)
        p = compute_passage(guide_lon, guide_lat, passage_rules, polygons)
        if p is None:
            continue
        new_lon = np.concatenate([lon[k:k + 1], p.lon_deg, lon[k + 1:k + 2]])
        new_lat = np.concatenate([lat[k:k + 1], p.lat_deg, lat[k + 1:k + 2]])
        new_lon, new_lat = _without_repeats(new_lon, new_lat)
        new_lon, new_lat = fewer_nodes(new_lon, new_lat, polygons, p.clearance_nm)
        track_lon = np.concatenate([lon[:k], new_lon, lon[k + 2:]])
        track_lat = np.concatenate([lat[:k], new_lat, lat[k + 2:]])
        legs = frozenset(range(k, k + new_lon.size - 1))
        others = frozenset(range(track_lon.size - 1)) - legs
        if land_legs(track_lon, track_lat, contains, skip_start_m, skip_end_m, others):
            continue
        return LegRepair(k, new_lon, new_lat, float(plat[first]),
                         float((plon[first] + 180.0) % 360.0 - 180.0),
                         passage_length_nm(new_lon, new_lat) - old_nm, p.clearance_nm)
    return None


def _scaled_land(polygons, lon: np.ndarray, lat: np.ndarray, margin_nm: float):
    """Land round a detour (unvalidated full-resolution rings clipped to its box) in a local
    frame where a degree of longitude is as long as a degree of latitude; (land, scale)."""
    import shapely

    c = float(np.cos(np.radians(np.mean(lat))))
    pad = margin_nm / 60.0 + 0.02
    shift = 360.0 * np.round(np.mean(lon) / 360.0)
    parts = land_in_box(polygons, float(lon.min() - shift - pad / c), float(lat.min() - pad),
                        float(lon.max() - shift + pad / c), float(lat.max() + pad))
    scaled = [shapely.transform(g, lambda xy: np.column_stack([(xy[:, 0] + shift) * c,
                                                               xy[:, 1]])) for g in parts]
    return scaled, c


def fewer_nodes(lon: np.ndarray, lat: np.ndarray, polygons, keep_nm: float
                ) -> tuple[np.ndarray, np.ndarray]:
    """A detour with as few nodes as keep every straight sub-leg `keep_nm` off land (and
    off it at all when 0): a grid path hugging a clearance ring has a node every cell or
    two; the bridge needs a handful (greedy: from each kept node the farthest one in clear
    sight)."""
    import shapely

    if lon.size <= 3:
        return lon, lat
    land, c = _scaled_land(polygons, lon, lat, keep_nm)
    if not land:
        return lon[[0, -1]], lat[[0, -1]]
    tree = shapely.STRtree(land)
    reach = keep_nm / 60.0

    def clear(i: int, j: int) -> bool:
        seg = shapely.LineString([(lon[i] * c, lat[i]), (lon[j] * c, lat[j])])
        near = tree.query(seg, predicate="dwithin", distance=reach) if reach > 0 else (
            tree.query(seg, predicate="intersects"))
        return near.size == 0

    keep, k = [0], 0
    while k < lon.size - 1:
        nxt = k + 1
        for m in range(lon.size - 1, k + 1, -1):
            if clear(k, m):
                nxt = m
                break
        keep.append(nxt)
        k = nxt
    return lon[keep], lat[keep]


def _without_repeats(lon: np.ndarray, lat: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Nodes with consecutive duplicates (closer than 1 m) dropped."""
    _, d = inverse(lon[:-1], lat[:-1], lon[1:], lat[1:])
    keep = np.concatenate([[True], np.atleast_1d(np.asarray(d)) > 1.0])
    return lon[keep], lat[keep]


def repaired_track(lon: np.ndarray, lat: np.ndarray, contains: LandTest, polygons,
                   base: PassageRules, rules: RepairRules = RepairRules(),
                   skip_start_m: float = 0.0, skip_end_m: float = 0.0
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray, list[LegRepair], list[int]]:
    """(nodes lon, lat, old leg of each new leg, repairs, old legs left on land) of a track
    with every leg that touches land replaced by its detour where one is found."""
    lon = np.unwrap(np.asarray(lon, dtype=float), period=360.0)
    lat = np.asarray(lat, dtype=float)
    bad = land_legs(lon, lat, contains, skip_start_m, skip_end_m)
    out_lon, out_lat, owner = [lon[:1]], [lat[:1]], []
    repairs, left = [], []
    for k in range(lon.size - 1):
        fix = (repair_leg(lon, lat, k, contains, polygons, base, rules, skip_start_m,
                          skip_end_m) if k in bad else None)
        if k in bad and fix is None:
            left.append(k)
        seg_lon = fix.lon_deg if fix is not None else lon[k:k + 2]
        seg_lat = fix.lat_deg if fix is not None else lat[k:k + 2]
        if fix is not None:
            repairs.append(fix)
        out_lon.append(seg_lon[1:])
        out_lat.append(seg_lat[1:])
        owner += [k] * (seg_lon.size - 1)
    return (np.concatenate(out_lon), np.concatenate(out_lat), np.array(owner, dtype=np.int64),
            repairs, left)


def _detour(plon: np.ndarray, plat: np.ndarray, ia: int, ib: int, polygons,
            passage_rules: PassageRules) -> tuple[np.ndarray, np.ndarray] | None:
    """Nodes of a detour between dense samples `ia` and `ib` (kept as its ends) on the fine
    grid, guided by the samples between them; None when no corridor has a way through."""
    step = max(1, round(0.5 * M_PER_NM / STEP_M))  # guide points every ~0.5 NM
    guide_lon = np.concatenate([plon[ia:ib:step], plon[ib:ib + 1]])
    guide_lat = np.concatenate([plat[ia:ib:step], plat[ib:ib + 1]])
    p = compute_passage(guide_lon, guide_lat, passage_rules, polygons)
    if p is None:
        return None
    new_lon, new_lat = _without_repeats(np.concatenate([plon[ia:ia + 1], p.lon_deg,
                                                        plon[ib:ib + 1]]),
                                        np.concatenate([plat[ia:ia + 1], p.lat_deg,
                                                        plat[ib:ib + 1]]))
    return fewer_nodes(new_lon, new_lat, polygons, p.clearance_nm)


def repaired_stretches(lon: np.ndarray, lat: np.ndarray, contains: LandTest, polygons,
                       base: PassageRules, rules: RepairRules = RepairRules(),
                       skip_start_m: float = 0.0, skip_end_m: float = 0.0
                       ) -> tuple[np.ndarray, np.ndarray, int]:
    """(nodes lon, lat, stretches left) of a track whose stretches with tested samples that
    `contains` flags are replaced by detours; a stretch runs from `windows_nm` before its
    first flagged sample to as far after its last (across nodes: a node that itself breaks
    the test moves), flagged samples closer than two windows sharing one. Stretches are
    repaired from the track's end backwards, so the part before each is unchanged."""
    lon = np.unwrap(np.asarray(lon, dtype=float), period=360.0)
    lat = np.asarray(lat, dtype=float)
    limit_m, left = np.inf, 0
    while lon.size >= 2:
        _, dist = inverse(lon[:-1], lat[:-1], lon[1:], lat[1:])
        dist = np.atleast_1d(np.asarray(dist, dtype=float))
        plon, plat, first, _, along = track_samples(lon, lat, dist, STEP_M)
        total = float(dist.sum())
        tested = (along >= skip_start_m) & (along <= total - skip_end_m) & (along < limit_m)
        hit = np.zeros(plon.size, dtype=bool)
        if tested.any():
            hit[tested] = np.asarray(contains(plon[tested], plat[tested]), dtype=bool)
        if not hit.any():
            break
        node_at = np.concatenate([first, [plon.size - 1]])  # sample index of each node
        hits = np.flatnonzero(hit)
        last = int(hits[-1])
        gap = np.diff(along[hits]) > 2.0 * rules.windows_nm[0] * M_PER_NM
        run_start = int(hits[np.flatnonzero(np.concatenate([[True], gap]))[-1]])
        fixed = False
        for window_nm, corridor_nm in zip(rules.windows_nm, rules.corridors_nm, strict=True):
            w_m = window_nm * M_PER_NM
            a_m = float(along[run_start]) - w_m
            while True:  # the stretch starts on a clean sample: earlier runs join it
                ia = int(np.searchsorted(along, max(a_m, 0.0)))
                earlier = hits[(hits <= ia) & (along[hits] > a_m - w_m)]
                if ia == 0 or earlier.size == 0:
                    break
                a_m = float(along[earlier[0]]) - w_m
            b_m = min(float(along[last]) + w_m, limit_m)  # not into a stretch behind it
            ib = min(int(np.searchsorted(along, b_m)), plon.size - 1)
            passage_rules = dataclasses.replace(
                base, clearances_nm=rules.clearances_nm, cell_nm=rules.cell_nm,
                fine_cell_nm=rules.cell_nm / 2.0, corridors_nm=(corridor_nm,), berth_nm=0.0,
                pilotage_nm=0.0, prefer_off_nm=2.0 * rules.clearances_nm[0],
                need_nm=rules.need_nm)
            detour = _detour(plon, plat, ia, ib, polygons, passage_rules)
            if detour is None:
                continue
            before, after = node_at < ia, node_at > ib
            new_lon = np.concatenate([lon[before], detour[0], lon[after]])
            new_lat = np.concatenate([lat[before], detour[1], lat[after]])
            k0 = int(before.sum())  # the detour's own legs: the rest sails the old lines
            legs = frozenset(range(k0, k0 + detour[0].size - 1))
            others = frozenset(range(new_lon.size - 1)) - legs
            if land_legs(new_lon, new_lat, contains, skip_start_m, skip_end_m, others):
                continue
            lon, lat, limit_m, fixed = new_lon, new_lat, float(along[ia]), True
            break
        if not fixed:  # left as it is; the samples a window before it are clean
            left += 1
            limit_m = float(along[run_start]) - rules.windows_nm[0] * M_PER_NM
    return lon, lat, left
