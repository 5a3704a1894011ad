"""3DDP (Shao 2012 style): forward DP on a great-circle grid with a time-fuel Pareto set per node.

The grid has stages equally spaced along the great circle and, at each inner stage, lateral
points on the perpendicular. From a point the ship may go to five points of the next stage
(lateral index change -2..+2, the "five headings"), at any of a set of RPM levels held for the
stage. Every node keeps the labels (arrival time, fuel) that are not dominated, with at most
one label per arrival-time bin (the least fuel for "the same arrival time"). At the arrival
port the labels form the ETA-vs-fuel Pareto front; the least-fuel label arriving by the RTA
is traced back to give the route and its per-stage RPM.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..geo.geodesy import great_circle_points
from .errors import NoRouteFoundError
from .geodesy import continuous_lon, direct, inverse
from .grid_search import UNSAFE_LEG_PENALTY_T
from .labels import prune_labels
from .legs import LegSailor

MAX_LATERAL_STEP = 2  # five headings: -2, -1, 0, +1, +2 lateral points


@dataclass(frozen=True)
class Ddp3Config:
    """Grid and label resolution of the 3DDP search."""

    stage_m: float = 200 * 1852.0
    n_lateral: int = 21
    lateral_m: float = 50 * 1852.0
    time_bin_s: float = 3600.0
    max_labels_per_node: int = 40
    late_window_s: float = 48 * 3600.0  # labels later than RTA + this are dropped


@dataclass(frozen=True)
class Ddp3Result:
    """Chosen route (one waypoint per stage), its per-leg RPM and the arrival Pareto front."""

    lon_deg: np.ndarray
    lat_deg: np.ndarray
    rpm: np.ndarray
    time_s: np.ndarray
    fuel_t: float
    pareto_eta_s: np.ndarray
    pareto_fuel_t: np.ndarray
    leg_evaluations: int


def ddp3_grid(
    sailor: LegSailor, start_lon: float, start_lat: float, end_lon: float, end_lat: float,
    cfg: Ddp3Config,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Node positions (stages x lateral) and a sea mask; the ports sit at the centre index."""
    end_lon = float(continuous_lon(end_lon, start_lon))
    _, total = inverse(start_lon, start_lat, end_lon, end_lat)
    n_stage = max(int(np.ceil(total / cfg.stage_m)), 2)
    gc_lon, gc_lat = great_circle_points(start_lon, start_lat, end_lon, end_lat, n_stage + 1)
    fwd, _ = inverse(gc_lon[:-1], gc_lat[:-1], gc_lon[1:], gc_lat[1:])
    course = np.r_[fwd, fwd[-1]]
    m = cfg.n_lateral
    centre = m // 2
    offsets = (np.arange(m) - centre) * cfg.lateral_m
    lon = np.empty((n_stage + 1, m))
    lat = np.empty((n_stage + 1, m))
    for s in range(n_stage + 1):
        az = np.where(offsets >= 0, course[s] + 90.0, course[s] - 90.0)
        p_lon, p_lat = direct(np.full(m, gc_lon[s]), np.full(m, gc_lat[s]), az, np.abs(offsets))
        lon[s] = continuous_lon(p_lon, start_lon)
        lat[s] = p_lat
    sea = ~np.asarray(sailor.on_land(lon.ravel(), lat.ravel()), bool).reshape(lon.shape)
    sea[0], sea[-1] = False, False
    sea[0, centre] = sea[-1, centre] = True
    lon[0, centre], lat[0, centre] = start_lon, start_lat
    lon[-1, centre], lat[-1, centre] = end_lon, end_lat
    return lon, lat, sea


def ddp3_route(
    sailor: LegSailor,
    start_lon: float,
    start_lat: float,
    end_lon: float,
    end_lat: float,
    depart_s: float,
    rta_s: float,
    rpm_levels: np.ndarray,
    config: Ddp3Config | None = None,
) -> Ddp3Result:
    """Forward 3DDP; returns the least-fuel route meeting `rta_s` and the arrival Pareto front."""
    cfg = config or Ddp3Config()
    lon, lat, sea = ddp3_grid(sailor, start_lon, start_lat, end_lon, end_lat, cfg)
    n_stage, m = lon.shape[0] - 1, lon.shape[1]
    centre = m // 2
    levels = np.asarray(rpm_levels, float)
    fastest = float(np.max(sailor.calm_speed_m_s(levels)))
    _, remain = inverse(lon.ravel(), lat.ravel(), np.full(lon.size, lon[-1, centre]),
                        np.full(lon.size, lat[-1, centre]))
    remain = remain.reshape(lon.shape)
    node = np.array([centre])
    t, f = np.array([depart_s]), np.array([0.0])
    parents, rpms, nodes = [], [], [node]
    evals = 0
    steps = np.arange(-MAX_LATERAL_STEP, MAX_LATERAL_STEP + 1)
    for s in range(n_stage):
        lab = np.repeat(np.arange(node.size), steps.size)
        tgt = node[lab] + np.tile(steps, node.size)
        valid = (tgt >= 0) & (tgt < m)
        lab, tgt = lab[valid], tgt[valid]
        valid = sea[s + 1, tgt]
        lab, tgt = lab[valid], tgt[valid]
        land = np.asarray(sailor.crosses_land(lon[s, node[lab]], lat[s, node[lab]],
                                              lon[s + 1, tgt], lat[s + 1, tgt]), bool)
        lab, tgt = lab[~land], tgt[~land]
        if lab.size == 0:
            raise NoRouteFoundError(f"3DDP: no sea connection from stage {s} to stage {s + 1}")
        lab = np.repeat(lab, levels.size)
        tgt = np.repeat(tgt, levels.size)
        rpm = np.tile(levels, lab.size // levels.size)
        legs = sailor.between(lon[s, node[lab]], lat[s, node[lab]], lon[s + 1, tgt],
                              lat[s + 1, tgt], t[lab], rpm)
        evals += lab.size
        t_new = t[lab] + legs.duration_s
        f_new = f[lab] + legs.fuel_t + np.where(legs.ok, 0.0, UNSAFE_LEG_PENALTY_T)
        too_late = t_new + remain[s + 1, tgt] / (1.1 * fastest) > rta_s + cfg.late_window_s
        if too_late.all():
            too_late = t_new > t_new.min()
        idx = np.flatnonzero(~too_late)
        keep = idx[prune_labels(tgt[idx], t_new[idx], f_new[idx], cfg.time_bin_s,
                                max_per_group=cfg.max_labels_per_node)]
        parents.append(lab[keep])
        rpms.append(rpm[keep])
        node, t, f = tgt[keep], t_new[keep], f_new[keep]
        nodes.append(node)
    front = prune_labels(np.zeros(t.size, np.int64), t, f, 1e-3)
    on_time = np.flatnonzero(t <= rta_s)
    best = int(on_time[np.argmin(f[on_time])]) if on_time.size else int(np.argmin(t))
    route_nodes = np.empty(n_stage + 1, dtype=np.int64)
    route_rpm = np.empty(n_stage)
    i = best
    for s in range(n_stage - 1, -1, -1):
        route_nodes[s + 1] = nodes[s + 1][i]
        route_rpm[s] = rpms[s][i]
        i = int(parents[s][i])
    route_nodes[0] = centre
    stages = np.arange(n_stage + 1)
    return Ddp3Result(
        lon[stages, route_nodes], lat[stages, route_nodes], route_rpm,
        np.array([depart_s, float(t[best])]), float(f[best]),
        t[front], f[front], evals,
    )
