"""Where a plan's depth near the coast was not checked (coarse grid only), said in the plan.

A coarse grid (> 1 arc-minute, e.g. the default ETOPO5 at 5 arc-minutes) averages sea and
land over several kilometres in its coastal cells and misses reefs and banks narrower than
a cell: its cells within `geo.coarse_coast.COAST_CELLS` of a cell holding GSHHG land give no
depth (no UKC constraint; the coastline decides there, as in the computed passages). This
module finds the legs of a finished plan that cross such cells where no fine grid covers the
water (grids without that mask: within `geo.nav_grid.COARSE_TRUST_CELLS` of their cells from
land), and the plan says how many and how long, so an officer knows where a chart (or a
finer `--bathymetry` grid) must decide.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from shiproute_core.geodesy import direct, inverse
from shiproute_core.units import M_PER_NM

from .geo.coarse_coast import COAST_CELLS, cells_at
from .geo.nav_grid import COARSE_TRUST_CELLS, M_PER_DEG_LAT, coarse_only
from .plan_types import RoutePlan

STEP_M = 0.5 * M_PER_NM  # samples along the track
PORT_M = 3000.0  # the berths at the track's ends are the harbour's business
BEARINGS_DEG = np.arange(0.0, 360.0, 30.0)  # land looked for in 12 directions ...
RADII_SHARE = (0.35, 0.7, 1.0)  # ... at these shares of the trust distance
#: farthest from land [cells] a point of a masked coastal cell lies along an axis: the reach
#: plus half a cell at each end
MASK_REACH_CELLS = COAST_CELLS + 1.0


def _samples(lon: np.ndarray, lat: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray,
                                                         np.ndarray]:
    """(lon, lat, leg index, distance along the track [m]) of points every ~STEP_M."""
    az, dist = inverse(lon[:-1], lat[:-1], lon[1:], lat[1:])
    dist = np.atleast_1d(np.asarray(dist, dtype=float))
    az = np.atleast_1d(np.asarray(az, dtype=float))
    n = np.maximum(1, np.ceil(dist / STEP_M).astype(int))
    leg = np.repeat(np.arange(lon.size - 1), n)
    first = np.concatenate([[0], np.cumsum(n)[:-1]])
    frac = (np.arange(leg.size) - first[leg] + 0.5) / n[leg]
    p_lon, p_lat = direct(lon[leg], lat[leg], az[leg], dist[leg] * frac)
    start = np.concatenate([[0.0], np.cumsum(dist)])
    return (np.asarray(p_lon, dtype=float), np.asarray(p_lat, dtype=float), leg,
            start[leg] + dist[leg] * frac)


def maybe_near_land(land, lon: np.ndarray, lat: np.ndarray, radius_m: float) -> np.ndarray:
    """False where the land mask's raster proves no land or coast lies within `radius_m`
    (its chessboard distance to the nearest non-sea cell, less one cell for where in the
    cells the point and the land lie, at the narrower side of a cell); True elsewhere."""
    cells = getattr(land, "sea_distance_cells", None)
    cell_deg = float(getattr(land, "cell_deg", 0.0))
    if cells is None or cell_deg <= 0.0:
        return np.ones(lon.size, dtype=bool)
    n_lat, n_lon = cells.shape
    i = np.clip(((lat + 90.0) / cell_deg).astype(np.int64), 0, n_lat - 1)
    j = np.clip((((lon + 180.0) % 360.0) / cell_deg).astype(np.int64), 0, n_lon - 1)
    d = cells[i, j].astype(float)
    narrow_m = cell_deg * M_PER_DEG_LAT * np.maximum(np.cos(np.radians(np.abs(lat) + cell_deg)),
                                                     1e-6)
    return (d - 1.0) * narrow_m <= radius_m


def near_land(is_land, lon: np.ndarray, lat: np.ndarray, radius_m: float) -> np.ndarray:
    """True where land lies within ~`radius_m` of a point (12 bearings x 3 radii, plus the
    point itself)."""
    out = np.asarray(is_land(lon, lat), dtype=bool).copy()
    for share in RADII_SHARE:
        for b in BEARINGS_DEG:
            o_lon, o_lat = direct(lon, lat, np.full(lon.size, b), np.full(lon.size,
                                                                          share * radius_m))
            out |= np.asarray(is_land(np.asarray(o_lon), np.asarray(o_lat)), dtype=bool)
    return out


def in_coastal_cells(grids: list, lon: np.ndarray, lat: np.ndarray) -> np.ndarray:
    """True where a point lies in a coastal cell (`geo.coarse_coast`) of any of the grids."""
    wrapped = (lon + 180.0) % 360.0 - 180.0
    out = np.zeros(lon.size, dtype=bool)
    for g in grids:
        out |= cells_at(g.coast_cells, wrapped, lat, g.lat0_deg, g.dlat_deg, g.lon0_deg,
                        g.dlon_deg, g.periodic)
    return out


def coarse_coastal_legs(lon: np.ndarray, lat: np.ndarray, bathymetry, is_land,
                        skip_legs: frozenset[int] = frozenset(),
                        land=None) -> tuple[list[int], float, float]:
    """(legs, NM of track, trust distance [NM]) of a polyline that run within the coarse
    grids' trust distance of land where no fine grid covers the water (`land`, a LandMask,
    lets its raster rule out open sea before the probes)."""
    coarse = [g for g in bathymetry.grids if g.is_coarse]
    if not coarse or lon.size < 2:
        return [], 0.0, 0.0
    masked = [g for g in coarse if g.coast_cells is not None]
    trust_m = (MASK_REACH_CELLS if masked else COARSE_TRUST_CELLS) * max(
        g.cell_deg for g in coarse) * M_PER_DEG_LAT
    lon = np.unwrap(np.asarray(lon, dtype=float), period=360.0)
    lat = np.asarray(lat, dtype=float)
    p_lon, p_lat, leg, along = _samples(lon, lat)
    keep = (along > PORT_M) & (along < along[-1] + 0.5 * STEP_M - PORT_M)
    keep &= ~np.isin(leg, np.fromiter(skip_legs, dtype=np.int64, count=len(skip_legs)))
    keep &= coarse_only(bathymetry, (p_lon + 180.0) % 360.0 - 180.0, p_lat)
    idx = np.flatnonzero(keep)
    if masked:  # the grid's own coastal cells: exactly where the optimiser had no depth
        hit = idx[in_coastal_cells(masked, p_lon[idx], p_lat[idx])]
    else:
        if land is not None and idx.size:
            idx = idx[maybe_near_land(land, p_lon[idx], p_lat[idx], trust_m)]
        if idx.size == 0:
            return [], 0.0, trust_m / M_PER_NM
        hit = idx[near_land(is_land, p_lon[idx], p_lat[idx], trust_m)]
    seg = np.diff(np.concatenate([[0.0], along]))  # ~STEP_M each
    return (sorted({int(k) for k in leg[hit]}), float(seg[hit].sum()) / M_PER_NM,
            trust_m / M_PER_NM)


def with_coarse_coast_note(plan: RoutePlan, under_keel, land) -> RoutePlan:
    """The plan with a warning (and `extra["depth_coarse_near_coast"]`) naming the legs whose
    depth near the coast was only checked on a coarse grid."""
    if under_keel is None or len(plan.waypoints) < 2:
        return plan
    lon, lat, _ = plan.track()
    skip = frozenset(k for a, b in plan.extra.get("fixed_passages", ()) for k in range(a, b))
    legs, nm, trust_nm = coarse_coastal_legs(lon, lat, under_keel.bathymetry, land.is_land,
                                             skip, land)
    if not legs:
        return plan
    coarse = max((g for g in under_keel.bathymetry.grids if g.is_coarse),
                 key=lambda g: g.cell_deg)
    note = (f"depth near the coast not checked: {len(legs)} leg(s), ~{nm:.0f} NM of the "
            f"track, cross {coarse.resolution_text} cells of {coarse.name} within "
            f"{COAST_CELLS} cells (up to ~{trust_nm:.0f} NM) of GSHHG land where no finer grid "
            "covers the water; coastal cells that coarse are smeared (sea and land averaged) "
            "and miss reefs and banks, so there they set no UKC constraint, the coastline "
            "decides and the chart must be checked (a finer grid: --bathymetry)")
    extra = {**plan.extra, "depth_coarse_near_coast": {
        "legs": legs, "track_nm": round(nm, 1), "within_nm": round(trust_nm, 2),
        "within_cells": COAST_CELLS, "ukc_constraint": False,
        "grid": coarse.name, "resolution": coarse.resolution_text}}
    return dataclasses.replace(plan, warnings=(*plan.warnings, note), extra=extra)
