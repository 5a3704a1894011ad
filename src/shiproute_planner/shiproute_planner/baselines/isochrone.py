"""Improved isochrone method (Roh 2013, after Hagiwara): constant RPM, land-aware, least fuel.

From every point of the current isochrone the ship sails a fan of headings around the bearing
to the arrival port for one time step at the fixed RPM (weather, speed loss and fuel from the
planner's ship model). A leg that touches land is shrunk to the longest fraction of the step
that stays at sea (Roh's interference check). The next isochrone keeps, in each cross-track
sector of the great circle, the point closest to the arrival port (among those with the fewest
legs over a seakeeping limit), which removes isochrone loops. Points that can reach the port
within a step finish there; among finished routes the least-fuel one is returned.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from shiproute_core.geodesy import cross_track_m, inverse, unwrap_near
from shiproute_core.units import M_PER_NM

from .errors import NoRouteFoundError
from .grid_search import UNSAFE_LEG_PENALTY_T
from .legs import LegSailor

SHRINK_FRACTIONS = (1.0, 0.75, 0.5, 0.25)


@dataclass(frozen=True)
class IsochroneConfig:
    """Time step, heading fan and sector width of the isochrone search."""

    step_s: float = 6 * 3600.0
    fan_half_deg: float = 60.0
    fan_step_deg: float = 5.0
    sector_m: float = 20 * M_PER_NM
    max_steps: int = 200


@dataclass(frozen=True)
class IsochroneRoute:
    """The least-fuel finished route: waypoints at each isochrone, times and fuel."""

    lon_deg: np.ndarray
    lat_deg: np.ndarray
    time_s: np.ndarray
    fuel_t: float
    n_isochrones: int
    leg_evaluations: int


def isochrone_route(
    sailor: LegSailor,
    start_lon_deg: float,
    start_lat_deg: float,
    end_lon_deg: float,
    end_lat_deg: float,
    depart_s: float,
    rpm: float,
    config: IsochroneConfig | None = None,
) -> IsochroneRoute:
    """Run the isochrone search at constant `rpm` and return the least-fuel finished route."""
    cfg = config or IsochroneConfig()
    end_lon = float(unwrap_near(end_lon_deg, start_lon_deg))
    offsets = np.arange(-cfg.fan_half_deg, cfg.fan_half_deg + 1e-9, cfg.fan_step_deg)
    lon, lat = np.array([start_lon_deg]), np.array([start_lat_deg])
    t, f = np.array([depart_s]), np.array([0.0])
    history: list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]] = []  # lon, lat, t, parent
    history.append((lon, lat, t, np.array([-1])))
    finished: list[tuple[float, float, int, int]] = []  # fuel, time, isochrone, index
    evals = 0
    first_finish_step = None
    for step in range(cfg.max_steps):
        # 1. direct finish from every point that can reach the port within one step
        n = lon.size
        e_lon, e_lat = np.full(n, end_lon), np.full(n, end_lat_deg)
        to_end = sailor.between(lon, lat, e_lon, e_lat, t, np.full(n, rpm))
        evals += n
        can = (to_end.duration_s <= cfg.step_s) & ~sailor.crosses_land(lon, lat, e_lon, e_lat)
        for i in np.flatnonzero(can):
            pen = 0.0 if to_end.ok[i] else UNSAFE_LEG_PENALTY_T
            finished.append(
                (f[i] + to_end.fuel_t[i] + pen, t[i] + to_end.duration_s[i], step, int(i)))
        if finished and first_finish_step is None:
            first_finish_step = step
        if first_finish_step is not None and step > first_finish_step:
            break
        # 2. fan of headings for one step, shrunk where the leg touches land
        brg, _ = inverse(lon, lat, e_lon, e_lat)
        par = np.repeat(np.arange(n), offsets.size)
        hdg = (np.repeat(brg, offsets.size) + np.tile(offsets, n)) % 360.0
        c_lon, c_lat, c_t, c_f, c_par = _sail_fan(sailor, lon, lat, t, f, par, hdg, rpm, cfg)
        evals += par.size
        if c_lon.size == 0:
            break
        # 3. prune: per cross-track sector keep the point nearest the arrival port
        xt = cross_track_m(c_lon, c_lat, start_lon_deg, start_lat_deg, end_lon, end_lat_deg)
        _, d_end = inverse(c_lon, c_lat, np.full(c_lon.size, end_lon),
                           np.full(c_lon.size, end_lat_deg))
        sector = np.floor(xt / cfg.sector_m).astype(np.int64)
        unsafe = np.floor(c_f / UNSAFE_LEG_PENALTY_T)  # legs over a limit so far
        order = np.lexsort((c_f, d_end, unsafe, sector))
        first = np.r_[True, sector[order][1:] != sector[order][:-1]]
        keep = order[first]
        lon, lat = unwrap_near(c_lon[keep], start_lon_deg), c_lat[keep]
        t, f = c_t[keep], c_f[keep]
        history.append((lon, lat, t, c_par[keep]))
    if not finished:
        raise NoRouteFoundError(
            f"isochrone search at {rpm:.1f} rpm did not reach the arrival port in "
            f"{cfg.max_steps} steps"
        )
    fuel, t_end, iso, idx = min(finished)
    pts_lon, pts_lat, pts_t = [end_lon], [end_lat_deg], [t_end]
    while iso >= 0 and idx >= 0:
        h_lon, h_lat, h_t, h_par = history[iso]
        pts_lon.append(float(h_lon[idx]))
        pts_lat.append(float(h_lat[idx]))
        pts_t.append(float(h_t[idx]))
        idx = int(h_par[idx])
        iso -= 1
    return IsochroneRoute(
        np.asarray(pts_lon[::-1]), np.asarray(pts_lat[::-1]), np.asarray(pts_t[::-1]),
        float(fuel), len(history), evals,
    )


def _sail_fan(
    sailor: LegSailor,
    lon: np.ndarray,
    lat: np.ndarray,
    t: np.ndarray,
    f: np.ndarray,
    par: np.ndarray,
    hdg: np.ndarray,
    rpm: float,
    cfg: IsochroneConfig,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Sail each (parent, heading) for a step; legs touching land retry with a shorter step."""
    out: list[tuple[np.ndarray, ...]] = []
    todo = np.arange(par.size)
    for frac in SHRINK_FRACTIONS:
        if todo.size == 0:
            break
        p = par[todo]
        legs = sailor.for_duration(lon[p], lat[p], hdg[todo], t[p], np.full(todo.size, rpm),
                                   cfg.step_s * frac)
        land = np.asarray(
            sailor.crosses_land(lon[p], lat[p], legs.end_lon_deg, legs.end_lat_deg), bool)
        sea = ~land
        pen = np.where(legs.ok, 0.0, UNSAFE_LEG_PENALTY_T)
        out.append((legs.end_lon_deg[sea], legs.end_lat_deg[sea], (t[p] + legs.duration_s)[sea],
                    (f[p] + legs.fuel_t + pen)[sea], p[sea]))
        todo = todo[land]
    if not out:
        return (np.zeros(0),) * 4 + (np.zeros(0, np.int64),)
    columns = tuple(np.concatenate(parts) for parts in zip(*out, strict=True))
    return columns  # type: ignore[return-value]  # zip(*out) loses the fixed 5-tuple shape
