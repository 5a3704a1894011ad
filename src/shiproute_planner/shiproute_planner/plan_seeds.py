"""The seed pool in a plan: the seeds a leg starts from and the route it offers back."""

from __future__ import annotations

import numpy as np
from shiproute_core.geodesy import unwrap_near

from .ga.pool import Seed, SeedPool, pool_key
from .geo.ports import Port
from .plan_types import RoutePlan
from .route.evaluation import RouteEvaluation
from .route.nearest import nearest_node
from .route.problem import RouteProblem
from .route.seeding import TrackSeed


def port_id(p: Port) -> str:
    return p.locode or f"{p.lat_deg:.2f},{p.lon_deg:.2f}"


def leg_seeds(problem: RouteProblem, pool: SeedPool | None, a: Port, b: Port, month: int,
           previous: RoutePlan | None, under_way: bool) -> tuple[list[TrackSeed], list]:
    """Seed tracks (the previous plan's part for this span, the pool's route) and the
    pool's ready genes of one optimised span."""
    out, genes = [], []
    if previous is not None:
        s = previous_span_seed(previous, problem, under_way)
        if s is not None:
            out.append(s)
    if pool is not None:
        stored = pool.get(pool_key(port_id(a), port_id(b), month))
        if stored is not None:
            out.append(TrackSeed("pool", np.array(stored.lon_deg), np.array(stored.lat_deg),
                                 np.array(stored.rpm)))
            if stored.genes:
                genes.append(("pool", np.array(stored.genes)))
    return out, genes


def previous_span_seed(previous: RoutePlan, problem: RouteProblem,
                       under_way: bool) -> TrackSeed | None:
    """The previous plan's route between this span's ends (the ship's position when under
    way, else the node nearest the span's start; the node nearest its end), its RPMs scaled
    by the ratio of its time on that route to this span's window (speed ~ RPM), so it
    arrives about on time: every span of a re-plan or of a front's next, later plan starts
    from the route before, not only the first (the ocean span after a strait is where most
    of the fuel is)."""
    lon, lat, t = previous.track()
    rpm = previous.leg_rpm()
    if under_way:
        later = np.flatnonzero(t > problem.depart_s)
        if later.size == 0:
            return None
        i0 = int(later[0]) - 1  # the leg the ship is on: it starts at the position
        t0 = problem.depart_s
    else:
        i0 = _nearest(lon, lat, problem.dep_lon_deg, problem.dep_lat_deg)
        t0 = float(t[i0])
    i0 = max(i0, 0)
    i1 = i0 + _nearest(lon[i0:], lat[i0:], problem.arr_lon_deg, problem.arr_lat_deg)
    if i1 <= i0 or not np.isfinite(rpm[i0:i1]).any():
        return None
    seg_lon, seg_lat = lon[i0:i1 + 1].copy(), lat[i0:i1 + 1].copy()
    seg_lon[0], seg_lat[0] = unwrap_near(problem.dep_lon_deg, seg_lon[1]), problem.dep_lat_deg
    seg_lon[-1] = unwrap_near(problem.arr_lon_deg, seg_lon[-2])
    seg_lat[-1] = problem.arr_lat_deg
    window_s = problem.rta_s - problem.depart_s
    scale = (float(t[i1]) - t0) / window_s if window_s > 0 else 1.0
    seg_rpm = np.asarray(rpm[i0:i1], dtype=float) * float(np.clip(scale, 0.8, 1.25))
    return TrackSeed("previous_plan", seg_lon, seg_lat, seg_rpm)


def _nearest(lon: np.ndarray, lat: np.ndarray, to_lon: float, to_lat: float) -> int:
    """Index of the node of (lon, lat) geodesically nearest to (to_lon, to_lat)."""
    near = nearest_node(lon, lat, to_lon, to_lat)
    return 0 if near is None else near[0]


def offer_to_pool(pool: SeedPool, problem: RouteProblem, a: Port, b: Port, month: int,
           ev: RouteEvaluation, source: str, genes: np.ndarray | None) -> None:
    pool.offer(Seed(pool_key(port_id(a), port_id(b), month),
                    tuple(map(float, ev.lon_deg[0])), tuple(map(float, ev.lat_deg[0])),
                    tuple(map(float, ev.legs["rpm"][0])), problem.objective,
                    float(ev.objective[0]), float(ev.violation[0]), float(ev.fuel_t[0]),
                    source, genes=() if genes is None else tuple(map(float, genes))))
