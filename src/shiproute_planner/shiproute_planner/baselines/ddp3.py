"""3DDP (Shao 2012 style): forward DP on a great-circle grid with a time-fuel Pareto set per node.

The grid has stages equally spaced along a reference line (the great circle, or the shortest
sea path where the circle crosses land; stages are added where the line bends round land)
and, at each inner stage, lateral points on the perpendicular. From a point the ship may go to
five points of the next stage (lateral index change -2..+2, the "five headings"; the ports
link to every point of the first and last stage), at any of a set of RPM levels held for the
stage. Every node keeps the labels (arrival time, fuel) that are not dominated, with at most
one label per arrival-time bin (the least fuel for "the same arrival time"). At the arrival
port the labels form the ETA-vs-fuel Pareto front; the least-fuel label arriving by the RTA
is traced back to give the route and its per-stage RPM.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from shiproute_core.geodesy import direct, inverse, unwrap_near
from shiproute_core.units import M_PER_NM

from .errors import NoRouteFoundError
from .grid_search import UNSAFE_LEG_PENALTY_T
from .labels import prune_labels
from .legs import LegSailor

MAX_LATERAL_STEP = 2  # five headings: -2, -1, 0, +1, +2 lateral points
MAX_STAGE_SPLITS = 6


@dataclass(frozen=True)
class Ddp3Config:
    """Grid and label resolution of the 3DDP search."""

    stage_m: float = 200 * M_PER_NM
    port_stage_m: float = 60 * M_PER_NM  # first/last inner stage this far from the ports
    n_lateral: int = 21
    lateral_m: float = 50 * M_PER_NM
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


def _stage_points(ref_lon: np.ndarray, ref_lat: np.ndarray, cfg: Ddp3Config, crosses_land
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Stage centres along the reference line: (lon, lat, course_deg, distance to nearer port).

    The first and last inner stages sit `cfg.port_stage_m` from the ports so the ports can
    reach them through narrow approaches; the rest are equally spaced about `cfg.stage_m`."""
    az, seg = inverse(ref_lon[:-1], ref_lat[:-1], ref_lon[1:], ref_lat[1:])
    cum = np.r_[0.0, np.cumsum(seg)]
    total = float(cum[-1])
    end_gap = min(cfg.port_stage_m, total / 4.0)
    n_mid = max(int(np.ceil((total - 2 * end_gap) / cfg.stage_m)), 1)
    d = np.r_[0.0, np.linspace(end_gap, total - end_gap, n_mid + 1), total]

    def at(dist: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        j = np.clip(np.searchsorted(cum, dist, side="right") - 1, 0, seg.size - 1)
        return direct(ref_lon[j], ref_lat[j], az[j], dist - cum[j])

    lon, lat = at(d)
    # where the line bends around land, a straight stage would cut the corner: add stages
    for _ in range(MAX_STAGE_SPLITS):
        bad = np.flatnonzero(crosses_land(lon[:-1], lat[:-1], lon[1:], lat[1:]))
        if bad.size == 0:
            break
        d = np.sort(np.r_[d, 0.5 * (d[bad] + d[bad + 1])])
        lon, lat = at(d)
    # course: direction of the reference line over the neighbouring stages
    fwd, _ = inverse(lon[:-1], lat[:-1], lon[1:], lat[1:])
    course = np.r_[fwd[0], fwd]
    to_port = np.minimum(d, total - d)
    return lon, lat, course, to_port


def ddp3_grid(
    sailor: LegSailor, ref_lon: np.ndarray, ref_lat: np.ndarray, cfg: Ddp3Config,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Node positions (stages x lateral) and a sea mask; the ports sit at the centre index.

    Lateral spacing is `cfg.lateral_m`, narrowed near the ports (a quarter of the distance to
    the nearer port) so the first and last stages stay reachable."""
    start_lon = float(ref_lon[0])
    c_lon, c_lat, course, to_port = _stage_points(ref_lon, ref_lat, cfg, sailor.crosses_land)
    n = c_lon.size
    m = cfg.n_lateral
    centre = m // 2
    lon = np.empty((n, m))
    lat = np.empty((n, m))
    for s in range(n):
        spacing = min(cfg.lateral_m, 0.25 * to_port[s])
        offsets = (np.arange(m) - centre) * spacing
        az = np.where(offsets >= 0, course[s] + 90.0, course[s] - 90.0)
        p_lon, p_lat = direct(np.full(m, c_lon[s]), np.full(m, c_lat[s]), az, np.abs(offsets))
        lon[s] = unwrap_near(p_lon, start_lon)
        lat[s] = p_lat
    sea = ~np.asarray(sailor.on_land(lon.ravel(), lat.ravel()), bool).reshape(lon.shape)
    sea[0], sea[-1] = False, False
    sea[0, centre] = sea[-1, centre] = True
    lon[0, centre], lat[0, centre] = ref_lon[0], ref_lat[0]
    lon[-1, centre], lat[-1, centre] = ref_lon[-1], ref_lat[-1]
    return lon, lat, sea


def ddp3_route(
    sailor: LegSailor,
    ref_lon: np.ndarray,
    ref_lat: np.ndarray,
    depart_s: float,
    rta_s: float,
    rpm_levels: np.ndarray,
    config: Ddp3Config | None = None,
) -> Ddp3Result:
    """Forward 3DDP around the reference line `ref_lon/ref_lat` (port to port: the great circle,
    or the sea lane where the circle crosses land); returns the least-fuel route meeting
    `rta_s` and the arrival Pareto front."""
    cfg = config or Ddp3Config()
    lon, lat, sea = ddp3_grid(sailor, np.asarray(ref_lon, float), np.asarray(ref_lat, float), cfg)
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
        # ports link to every point of the first/last stage (their approaches are often
        # narrow); in open water a stage moves at most MAX_LATERAL_STEP points sideways
        st = np.arange(-(m - 1), m) if s in (0, n_stage - 1) else steps
        lab = np.repeat(np.arange(node.size), st.size)
        tgt = node[lab] + np.tile(st, node.size)
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
