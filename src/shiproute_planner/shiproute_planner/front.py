"""The time-fuel front of a voyage: plans from "as fast as safe" to "slowest that meets the
latest arrival", each the least-fuel route for its arrival time, as one product.

The fastest end is planned with the ETA objective (earliest arrival within every constraint:
seakeeping, engine, land, depth); the slowest end and the points between are least-fuel plans
whose RTAs are spread evenly between that earliest arrival and the voyage's RTA (the latest
arrival). Each plan is seeded with its faster neighbour's route. A plan that is dominated
(not faster, yet not less fuel, than another) is left out of the Pareto set and named in the
front's notes; every plan keeps its own feasibility flags and warnings.
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from shiproute_core.units import M_S_PER_KNOT

from .errors import InvalidVoyageError
from .plan_request import Budget, PlanRequest, run_request
from .plan_types import RoutePlan

MIN_SPREAD_S = 1800.0  # an RTA window narrower than this above the earliest arrival: one plan


@dataclass(frozen=True)
class TimeFuelFront:
    """Pareto set of ETA vs fuel, fastest first (ETA rising, fuel falling)."""

    plans: tuple[RoutePlan, ...]
    earliest_eta_s: float  # arrival of the as-fast-as-safe plan [POSIX s]
    latest_arrival_s: float  # the voyage RTA [POSIX s]
    notes: tuple[str, ...]
    compute_time_s: float

    @property
    def monotone(self) -> bool:
        """More time, less fuel along the whole front."""
        return all(b.eta_s > a.eta_s and b.total_fuel_t < a.total_fuel_t
                   for a, b in zip(self.plans, self.plans[1:], strict=False))


def pareto(plans: list[RoutePlan]) -> tuple[list[RoutePlan], list[RoutePlan]]:
    """(non-dominated plans, fastest first; dominated ones): a plan is kept when it burns
    less fuel than every faster (or equally fast) plan."""
    keep: list[RoutePlan] = []
    dropped: list[RoutePlan] = []
    for p in sorted(plans, key=lambda p: (p.eta_s, p.total_fuel_t)):
        if keep and p.total_fuel_t >= keep[-1].total_fuel_t:
            dropped.append(p)
        else:
            keep.append(p)
    return keep, dropped


#: one plan of the front: (index, objective, latest arrival [POSIX s], faster neighbour)
PlanOne = Callable[[int, str, float, RoutePlan | None], RoutePlan]


#: windows tried for the fastest plan, as multiples of the great circle at top calm speed
FAST_WINDOWS = (1.15, 1.4)


def top_speed_s(origin: str, destination: str, ship: Any, loading: str = "") -> float:
    """Great-circle time between the ports at the ship's top calm-water speed [s]: a lower
    bound of any arrival, and the scale of the window the fastest plan is searched in."""
    from shiproute_core.geodesy import inverse

    from .checks.voyage import max_calm_speed_kn
    from .geo.landmask import default_land_mask
    from .geo.ports import resolve_port
    from .ship import load_ship
    from .voyage_ship import loaded_ship

    land = default_land_mask()
    a, b = resolve_port(origin, land), resolve_port(destination, land)
    dist_m = float(inverse(a.lon_deg, a.lat_deg, b.lon_deg, b.lat_deg)[1])
    spec = loaded_ship(ship, loading) if loading else load_ship(ship)
    return dist_m / (max_calm_speed_kn(spec) * M_S_PER_KNOT)


def build_front(plan_one: PlanOne, depart_s: float, rta_s: float, n_points: int,
                top_s: float | None = None) -> TimeFuelFront:
    """The front from `plan_one`: the ETA-objective plan (index 0) fixes the earliest safe
    arrival, then `n_points - 1` least-fuel plans with RTAs spread evenly from it to `rta_s`,
    each seeded with its faster neighbour; dominated plans are left out and noted.

    The route encoding has as many stages as the RTA window holds, so the fastest plan is
    searched in a window just above `top_s` (great circle at top calm speed; FAST_WINDOWS),
    widening while the plan arrives late or breaks a constraint, and at last in the whole
    window up to `rta_s`."""
    t0 = time.perf_counter()
    if not 2 <= n_points <= 25:
        raise InvalidVoyageError(f"front points must be 2..25, got {n_points}")
    notes: list[str] = []
    fastest = None
    for factor in FAST_WINDOWS if top_s else ():
        window_end = depart_s + factor * float(top_s or 0.0)
        if window_end >= rta_s:
            break
        trial = plan_one(0, "eta", window_end, None)
        if trial.feasible:
            fastest = trial
            break
        notes.append(f"fastest plan: no feasible arrival within {factor:g} x the great circle "
                     f"at top speed ({'; '.join(trial.infeasible_reasons)}); window widened")
    if fastest is None:
        fastest = plan_one(0, "eta", rta_s, None)
    earliest = min(fastest.eta_s, rta_s)
    plans = [fastest]
    if rta_s - earliest < MIN_SPREAD_S:
        notes.append(f"the RTA leaves {(rta_s - earliest) / 60:.0f} min above the earliest "
                     "safe arrival: the front is one plan")
    else:
        prev = fastest
        for k in range(1, n_points):
            prev = plan_one(k, "fuel", earliest + (rta_s - earliest) * k / (n_points - 1), prev)
            plans.append(prev)
    if not fastest.feasible:
        notes.append("the fastest plan is infeasible: " + "; ".join(fastest.infeasible_reasons))
    keep, dropped = pareto(plans)
    for p in dropped:
        notes.append(f"plan {p.plan_id} ({(p.eta_s - depart_s) / 3600:.1f} h, "
                     f"{p.total_fuel_t:.1f} t) left out: a faster plan burns no more fuel")
    return TimeFuelFront(tuple(keep), earliest, rta_s, tuple(notes), time.perf_counter() - t0)


def plan_front(req: PlanRequest, forecast: Any = None, *,
               progress: Callable[[int, RoutePlan], None] | None = None,
               **extra: Any) -> TimeFuelFront:
    """The front of `req`'s voyage with `req.front_points` plans within `req.budget` (wall
    time or route evaluations of the whole front, shared equally); `extra` as
    `run_request` (land mask, bathymetry, zones, ...). `progress(k, plan)` after each plan."""
    t0 = time.perf_counter()
    n = req.front_points
    if req.via:
        raise InvalidVoyageError("the time-fuel front is planned without --via ports")

    def budget(k: int) -> Budget:
        if req.budget.evaluations:
            return Budget(math.inf, max(req.budget.evaluations // n, 1))
        left = (req.budget.wall_s - (time.perf_counter() - t0)) / (n - k)
        return Budget(max(left, 0.25 * req.budget.wall_s / n), 0)

    def one(k: int, objective: str, rta_s: float, previous: RoutePlan | None) -> RoutePlan:
        r = dataclasses.replace(req, objective=objective, rta_s=rta_s, budget=budget(k),
                                seed=req.seed + k)
        plan = run_request(r, forecast, previous_plan=previous, **extra)
        if progress is not None:
            progress(k, plan)
        return plan

    top = top_speed_s(req.origin, req.destination, req.ship, req.loading)
    return build_front(one, req.depart_s, req.rta_s, n, top)
