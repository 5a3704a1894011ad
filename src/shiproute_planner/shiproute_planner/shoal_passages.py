"""Shoals on a sea lane as computed deep-water passages.

The `searoute` lane is drawn for any ship and hugs coasts across banks a deep-draft ship must
stay off (the North Frisian banks west of Sylt read 11-13 m in ETOPO5 on the lane Elbe ->
Skagen). Where a leg's sea lane runs over water shallower than the ship needs (draft, squat
at 12 kn, margin) for at least `SHALLOW_MIN_NM`, where the navigable-water grid trusts the
depth (`trusted_depth_m`: a coarse grid's cells near the coast read unknown), the stretch
from `LEAD_NM` before the shoal to `LEAD_NM` after it becomes a passage of its own, computed
on the navigable-water grid like a strait's (`route.passages`: full-resolution land,
clearance, the ship's depth, the corridor widened before the depth limit is given up)
between two gates on the lane; the optimiser plans the open sea on either side. Pilotage
waters (`PORT_SKIP_NM` round each port) are left to the port's approach.
"""

from __future__ import annotations

import functools

import numpy as np
from shapely.errors import ShapelyError
from shiproute_core.geodesy import densify_track, inverse, wrap_lon
from shiproute_core.units import M_PER_NM

from .route.approach_shoals import ShoalLimit
from .straits import Strait

SHALLOW_MIN_NM = 1.0  # a shoal shorter than this along the lane is left to the optimiser
LEAD_NM = 30.0  # gates this far before and after the shoal along the lane
MIN_LEAD_NM = 10.0  # a gate nearer its shoal than this (pilotage limits) leaves no room
PORT_SKIP_NM = 10.0  # pilotage waters round each port: the approach's business
STEP_M = 0.5 * M_PER_NM  # lane sampling


def shoal_stretches(dist_m: np.ndarray, depth_m: np.ndarray, need_m: float
                    ) -> list[tuple[float, float]]:
    """(start, end) [m along the lane] of the gated stretches: shoals (depth known and below
    `need_m` over >= `SHALLOW_MIN_NM`) outside the ports' pilotage waters, each widened by
    `LEAD_NM` and merged where they overlap, clipped to the pilotage limits. A stretch whose
    gate would lie on known shallow water or nearer its shoal than `MIN_LEAD_NM` (a shoal
    reaching into a port's approach: no room to steer round it from the gate) is left to the
    port's approach passage, computed with the same depth limit."""
    lo, hi = PORT_SKIP_NM * M_PER_NM, float(dist_m[-1]) - PORT_SKIP_NM * M_PER_NM
    shallow = np.isfinite(depth_m) & (depth_m < need_m) & (dist_m > lo) & (dist_m < hi)
    found: list[tuple[float, float, float, float]] = []  # gate, shoal start, end, gate
    k = 0
    while k < shallow.size:
        if not shallow[k]:
            k += 1
            continue
        m = k
        while m + 1 < shallow.size and shallow[m + 1]:
            m += 1
        s0, s1 = float(dist_m[k]), float(dist_m[m])
        if s1 - s0 >= SHALLOW_MIN_NM * M_PER_NM - 1.0:
            a = max(s0 - LEAD_NM * M_PER_NM, lo)
            b = min(s1 + LEAD_NM * M_PER_NM, hi)
            if found and a <= found[-1][3]:
                found[-1] = (found[-1][0], found[-1][1], s1, max(found[-1][3], b))
            elif b > a:
                found.append((a, s0, s1, b))
        k = m + 1
    out = []
    room = MIN_LEAD_NM * M_PER_NM - 1.0
    for a, s0, s1, b in found:
        gate_depth = depth_m[np.clip(np.searchsorted(dist_m, (a, b)), 0, dist_m.size - 1)]
        if s0 - a >= room and b - s1 >= room and not np.any(np.isfinite(gate_depth)
                                                            & (gate_depth < need_m)):
            out.append((a, b))
    return out


def _lane_of(a, b) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """The sea lane between two ports, densified to `STEP_M` (continuous longitudes), and
    the distance along it [m] at each point."""
    from .geo.sea_lanes import lane_key

    return _lane_between(*lane_key(a.lon_deg, a.lat_deg, b.lon_deg, b.lat_deg))


@functools.lru_cache(maxsize=32)
def _lane_between(lon0: float, lat0: float, lon1: float, lat1: float
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """`_lane_of` for rounded end points, kept (read-only): a re-plan's legs beyond the
    ship's position are the previous plan's, and their lanes ~10 ms each to densify."""
    from .geo.sea_lanes import searoute_coords

    coords = searoute_coords(lon0, lat0, lon1, lat1)
    if coords is None or len(coords) < 2:
        return None
    lon, lat = densify_track(np.unwrap(coords[:, 0], period=360.0), coords[:, 1], STEP_M)
    lon, lat = np.array(lon, dtype=float), np.array(lat, dtype=float)
    _, seg = inverse(lon[:-1], lat[:-1], lon[1:], lat[1:])
    dist = np.concatenate([[0.0], np.cumsum(seg)])
    for a in (lon, lat, dist):
        a.setflags(write=False)
    return lon, lat, dist


def trusted_depth_m(bathymetry, lon: np.ndarray, lat: np.ndarray, need_m: float,
                    polygons=None) -> np.ndarray:
    """Depth [m] at lane points as the navigable-water grid trusts it (`geo.nav_grid`): a
    point shallower than `need_m` where only coarse grids answer reads NaN when it lies
    nearer the full-resolution coast than `COARSE_TRUST_CELLS` of their cells (the coastline
    decides there, and the passage would not see the shoal either)."""
    from .geo.nav_grid import COARSE_TRUST_CELLS, coarse_only

    depth = np.asarray(bathymetry.depth_m(lon, lat), dtype=float)
    coarse = [g.cell_deg for g in bathymetry.grids if g.is_coarse]
    if not coarse:
        return depth
    check = np.flatnonzero(np.isfinite(depth) & (depth < need_m)
                           & coarse_only(bathymetry, lon, lat))
    trust_deg = COARSE_TRUST_CELLS * max(coarse)
    # runs of nearby points share one small box of land (a lane's shoals lie in a few places)
    breaks = np.flatnonzero(np.diff(check) > 100) + 1
    for run in np.split(check, breaks) if check.size else []:
        depth[run[_near_coast(lon[run], lat[run], trust_deg, polygons)]] = np.nan
    return depth


def _near_coast(lon: np.ndarray, lat: np.ndarray, within_deg: float, polygons) -> np.ndarray:
    """True where a point lies nearer full-resolution land than `within_deg` (of latitude)."""
    import shapely

    from .geo.nav_grid import land_in_box
    from .route.passages import best_land_polygons

    c_lon = np.asarray(wrap_lon(lon), dtype=float)
    pad_lat = within_deg + 0.05
    pad_lon = pad_lat / max(float(np.cos(np.radians(np.max(np.abs(lat))))), 0.1)
    parts = land_in_box(polygons if polygons is not None else best_land_polygons(),
                        float(np.min(c_lon)) - pad_lon, float(np.min(lat)) - pad_lat,
                        float(np.max(c_lon)) + pad_lon, float(np.max(lat)) + pad_lat)
    if not parts:
        return np.zeros(lon.shape, dtype=bool)
    scale = np.cos(np.radians(float(np.mean(lat))))  # local frame: degrees of latitude
    # per part, no union: GSHHG rings are not validated (`land_in_box`), distance needs none
    land = shapely.transform(np.asarray(parts, dtype=object), lambda xy: xy * [scale, 1.0])
    pts = shapely.points(c_lon * scale, lat)
    return np.min(shapely.distance(pts[:, None], land[None, :]), axis=1) < within_deg


def lane_shoal_limit(under_keel) -> ShoalLimit | None:
    """The shoals a ship's port approaches end past (`route.approach_shoals`): lane water
    trusted (`trusted_depth_m`) to be shallower than the passages' depth limit, the shoals
    `shoal_stretches` leaves to the approaches; None for a ship without a depth limit."""
    from .coastal_passages import passage_rules

    rules = passage_rules(under_keel)
    need_m = rules.required_depth_m
    if need_m is None:
        return None
    bathymetry = rules.bathymetry
    return ShoalLimit(lambda lon, lat: trusted_depth_m(bathymetry, lon, lat, need_m), need_m)


def route_shoals(ports: list, canal_legs: dict, strait_legs: dict, via_rta: list,
                 under_keel, need_m: float | None) -> tuple[list, dict, dict, list, list[str]]:
    """Ports with shoal gates inserted where the sea lane of an open-sea leg (not a canal or
    strait) crosses known water shallower than `need_m`; returns (ports, canal legs and
    strait legs re-indexed (shoal passages join the strait legs), via RTAs aligned to the
    new ports, notes for the plan). Nothing changes without a depth limit."""
    from .geo.ports import Port

    if under_keel is None or need_m is None:
        return ports, canal_legs, strait_legs, via_rta, []
    rtas = list(via_rta) + [None] * (len(ports) - 2 - len(via_rta))
    out, out_rta, canals, straits, notes = [ports[0]], [], {}, {}, []
    for k in range(len(ports) - 1):
        a, b = ports[k], ports[k + 1]
        here = len(out) - 1
        if k in canal_legs:
            canals[here] = canal_legs[k]
        elif k in strait_legs:
            straits[here] = strait_legs[k]
        else:
            lane = _lane_of(a, b)
            if lane is not None:
                lon, lat, dist = lane
                try:
                    depth = trusted_depth_m(under_keel.bathymetry, lon, lat, need_m)
                except (ValueError, OSError, MemoryError, ShapelyError) as exc:
                    notes.append(f"shoals on the sea lane {a.name} -> {b.name} not checked "
                                 f"({exc}); the optimiser's depth constraint alone applies")
                    depth = np.full(lon.shape, np.nan)
                for s0, s1 in shoal_stretches(dist, depth, need_m):
                    i0, i1 = (int(np.searchsorted(dist, s)) for s in (s0, s1))
                    i1 = min(max(i1, i0 + 1), lon.size - 1)
                    shoal = (dist >= s0) & (dist <= s1) & (depth < need_m)
                    j = int(np.flatnonzero(shoal)[np.argmin(depth[shoal])]) if shoal.any() \
                        else (i0 + i1) // 2
                    name = (f"deep-water passage past the shoal at {lat[j]:.2f}, "
                            f"{float(wrap_lon(lon[j])):.2f} ({depth[j]:.0f} m on the sea lane)")
                    straits[len(out)] = (Strait(name, ((lat[i0], lon[i0]), (lat[i1], lon[i1]))),
                                         lon[i0:i1 + 1].copy(), lat[i0:i1 + 1].copy())
                    out.append(Port(f"{name} gate", "", float(lat[i0]),
                                    float(wrap_lon(lon[i0]))))
                    out.append(Port(f"{name} gate", "", float(lat[i1]),
                                    float(wrap_lon(lon[i1]))))
                    out_rta += [None, None]
                    notes.append(f"the sea lane {a.name} -> {b.name} crosses water shallower "
                                 f"than the ship's {need_m:.1f} m ({depth[j]:.0f} m at "
                                 f"{lat[j]:.2f}, {float(wrap_lon(lon[j])):.2f}): a "
                                 f"deep-water passage is computed over "
                                 f"{(s1 - s0) / M_PER_NM:.0f} NM there")
        out.append(b)
        if k < len(ports) - 2:
            out_rta.append(rtas[k])
    return out, canals, straits, out_rta, notes
