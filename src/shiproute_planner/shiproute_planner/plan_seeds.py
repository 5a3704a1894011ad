"""The seed pool in a plan: the seeds a leg starts from and the route it offers back."""

from __future__ import annotations

import numpy as np

from .ga.pool import Seed, SeedPool, pool_key
from .geo.ports import Port
from .plan_types import RoutePlan
from .route.evaluation import RouteEvaluation
from .route.problem import RouteProblem
from .route.seeding import TrackSeed, shift_track


def port_id(p: Port) -> str:
    return p.locode or f"{p.lat_deg:.2f},{p.lon_deg:.2f}"


def leg_seeds(problem: RouteProblem, pool: SeedPool | None, a: Port, b: Port, month: int,
           previous: RoutePlan | None, position) -> tuple[list[TrackSeed], list]:
    out, genes = [], []
    if previous is not None:
        lon, lat, t = previous.track()
        if position is not None:
            s = shift_track(lon, lat, t, previous.leg_rpm(), problem.dep_lon_deg,
                            problem.dep_lat_deg, problem.depart_s)
        else:
            s = TrackSeed("previous_plan", lon, lat, previous.leg_rpm())
        if s is not None and s.lon_deg.size >= 2:
            out.append(s)
    if pool is not None:
        stored = pool.get(pool_key(port_id(a), port_id(b), month))
        if stored is not None:
            out.append(TrackSeed("pool", np.array(stored.lon_deg), np.array(stored.lat_deg),
                                 np.array(stored.rpm)))
            if stored.genes:
                genes.append(("pool", np.array(stored.genes)))
    return out, genes


def offer_to_pool(pool: SeedPool, problem: RouteProblem, a: Port, b: Port, month: int,
           ev: RouteEvaluation, source: str, genes: np.ndarray | None) -> None:
    pool.offer(Seed(pool_key(port_id(a), port_id(b), month),
                    tuple(map(float, ev.lon_deg[0])), tuple(map(float, ev.lat_deg[0])),
                    tuple(map(float, ev.legs["rpm"][0])), problem.objective,
                    float(ev.objective[0]), float(ev.violation[0]), float(ev.fuel_t[0]),
                    source, genes=() if genes is None else tuple(map(float, genes))))
