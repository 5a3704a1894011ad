"""Leg schedule of a multi-port voyage: the time to the RTA split over the legs by what the
ship can do, optimised over the whole voyage at once.

Each sea leg k of estimated sea distance D_k sailed in time T_k at the steady speed D_k/T_k
burns F_k(T_k) = T_k * r(D_k / T_k), r the ship's calm-water fuel rate at that speed (fitted
to the ship model over its RPM range). The schedule minimises the voyage's sum of F_k subject
to every leg lying between full speed (with a margin for weather and detours) and the
slowest RPM, each port's arrival window (waiting at anchor for an earliest arrival is
allowed), the berth times and the final RTA. Minimising the sum equalises the marginal fuel
per hour (dF/dT) across legs wherever no window binds, the optimality condition of the
allocation. A window or RTA that cannot be met is relaxed (lateness costs far more than
fuel) and the schedule states why, so the voyage is planned best effort and flagged.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from datetime import UTC, datetime

import numpy as np
from scipy.optimize import minimize

SPEED_MARGIN = 0.92  # a leg planned at full speed must leave room for weather and detours
WINDOW_MARGIN = 0.01  # share of a leg's shortest time kept before a latest arrival ...
WINDOW_MARGIN_MIN_H, WINDOW_MARGIN_MAX_H = 0.25, 3.0  # ... within these bounds [h]
_LATE_COST = 1e4  # objective units per hour of missed window (fuel is ~1 per leg)


@dataclass(frozen=True)
class LegSpec:
    """One leg of the schedule: sea distance, fixed duration (canals) or None, and the call at
    its end port (window POSIX s, None = open; berth s)."""

    name: str  # the end port
    distance_m: float
    fixed_s: float | None = None
    earliest_s: float | None = None
    latest_s: float | None = None
    berth_s: float = 0.0


@dataclass(frozen=True)
class Schedule:
    """Arrival, berth start and departure per end port [POSIX s]; feasible or the reasons."""

    arrival_s: tuple[float, ...]
    berth_start_s: tuple[float, ...]
    departure_s: tuple[float, ...]  # from the leg's end port (the last one: its arrival)
    sail_s: tuple[float, ...]
    feasible: bool
    reasons: tuple[str, ...]
    fuel_estimate_t: float


def iso(t_s: float) -> str:
    """POSIX s -> 'YYYY-MM-DDTHH:MMZ'."""
    return datetime.fromtimestamp(t_s, UTC).strftime("%Y-%m-%dT%H:%MZ")


@dataclass(frozen=True)
class FuelRate:
    """Calm-water fuel rate [t/h] as a smooth function of speed [m/s] on [v_min, v_max]."""

    v_min_m_s: float
    v_max_m_s: float
    coef: tuple[float, ...]  # polynomial in speed, highest power first

    def rate(self, v: np.ndarray) -> np.ndarray:
        """Fuel rate [t/h] at speed `v`."""
        return np.polyval(self.coef, v)

    def rate_slope(self, v: np.ndarray) -> np.ndarray:
        """d rate / d v [t/h per m/s]."""
        return np.polyval(np.polyder(np.array(self.coef)), v)


def fuel_rate_of(speed_fuel: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
                 rpm_min: float, rpm_max: float) -> FuelRate:
    """Fit the calm-water fuel rate of a ship: `speed_fuel(rpm)` -> (speed m/s, fuel t/h)."""
    rpm = np.linspace(rpm_min, rpm_max, 25)
    v, f = speed_fuel(rpm)
    ok = np.isfinite(v) & np.isfinite(f) & (v > 0)
    v, f = v[ok], f[ok]
    if v.size < 4:
        raise ValueError("the ship model gives no calm-water speeds over its RPM range")
    return FuelRate(float(v.min()), float(v.max()), tuple(map(float, np.polyfit(v, f, 3))))


def _bounds_s(legs: Sequence[LegSpec], fr: FuelRate) -> tuple[np.ndarray, np.ndarray]:
    """(shortest, longest) sailing time per leg [s]: margin-reduced full speed, slowest RPM."""
    lo, hi = [], []
    for leg in legs:
        if leg.fixed_s is not None:
            lo.append(leg.fixed_s)
            hi.append(leg.fixed_s)
            continue
        d = max(leg.distance_m, 1.0)
        lo.append(d / (SPEED_MARGIN * fr.v_max_m_s))
        hi.append(max(d / fr.v_min_m_s, lo[-1]))
    return np.array(lo), np.array(hi)


def plan_schedule(legs: Sequence[LegSpec], depart_s: float, rta_s: float,
                  fr: FuelRate) -> Schedule:
    """The fuel-optimal leg schedule (see the module docstring)."""
    n = len(legs)
    lo_s, hi_s = _bounds_s(legs, fr)
    berth_h = np.array([leg.berth_s for leg in legs]) / 3600.0
    berth_h[-1] = 0.0  # at the destination the voyage ends on arrival
    lo, hi = lo_s / 3600.0, hi_s / 3600.0
    dist = np.array([leg.distance_m for leg in legs])
    sea = np.array([leg.fixed_s is None for leg in legs])
    # objective scale: the fuel at full speed (a cubic fitted over the RPM range may read
    # below zero at the slowest speed, and a negative scale would maximise the fuel)
    f_scale = abs(float(np.sum(_leg_fuel(lo, dist, fr, sea)))) or 1.0
    earliest = [None if leg.earliest_s is None else (leg.earliest_s - depart_s) / 3600.0
                for leg in legs]
    latest = [None if leg.latest_s is None else (leg.latest_s - depart_s) / 3600.0
              for leg in legs]
    rta_h = (rta_s - depart_s) / 3600.0
    latest[-1] = rta_h if latest[-1] is None else min(latest[-1], rta_h)
    # variables: sail T (n), wait W (n), lateness s (n) [h]; arrival A_k = sum T_j<=k + sum
    # (W + B)_j<k
    tri = np.tril(np.ones((n, n)))
    tri_strict = tri - np.eye(n)

    def arrival(x: np.ndarray) -> np.ndarray:
        return tri @ x[:n] + tri_strict @ (x[n:2 * n] + berth_h)

    def objective(x: np.ndarray) -> float:
        return float(np.sum(_leg_fuel(x[:n], dist, fr, sea)) / f_scale
                     + _LATE_COST * np.sum(x[2 * n:]) / max(rta_h, 1.0))

    def gradient(x: np.ndarray) -> np.ndarray:
        g = np.zeros(3 * n)
        g[:n] = _leg_fuel_slope(x[:n], dist, fr, sea) / f_scale
        g[2 * n:] = _LATE_COST / max(rta_h, 1.0)
        return g

    cons = []
    for k in range(n):
        row_a = np.concatenate([tri[k], tri_strict[k], np.zeros(n)])
        late, early = latest[k], earliest[k]
        if late is not None:  # A_k - s_k <= latest
            row = row_a.copy()
            row[2 * n + k] = -1.0
            off = float(tri_strict[k] @ berth_h)
            if k < n - 1:  # aim a little before a port's latest arrival (weather, detours)
                off += min(WINDOW_MARGIN_MAX_H, max(WINDOW_MARGIN_MIN_H,
                                                    WINDOW_MARGIN * float(lo[k])))
            cons.append({"type": "ineq", "jac": (lambda x, r=row: -r),
                         "fun": (lambda x, r=row, c=late - off: c - r @ x)})
        if early is not None:  # A_k + W_k + s_k >= earliest (waiting allowed)
            row = row_a.copy()
            row[n + k] += 1.0
            row[2 * n + k] += 1.0
            off = float(tri_strict[k] @ berth_h)
            cons.append({"type": "ineq", "jac": (lambda x, r=row: r),
                         "fun": (lambda x, r=row, c=early - off: r @ x - c)})
    x0 = np.concatenate([_start_times(lo, hi, rta_h - berth_h.sum()), np.zeros(2 * n)])
    bounds = ([(float(a), float(b)) for a, b in zip(lo, hi, strict=True)]
              + [(0.0, None)] * n + [(0.0, None)] * n)
    res = minimize(objective, x0, jac=gradient, bounds=bounds, constraints=cons,
                   method="SLSQP", options={"maxiter": 500, "ftol": 1e-10})
    x = np.clip(res.x, [b[0] for b in bounds], [b[1] if b[1] is not None else np.inf
                                                for b in bounds])
    arr_h = arrival(x)
    start_h = arr_h + x[n:2 * n]
    dep_h = start_h + berth_h
    reasons = _reasons(legs, arr_h, start_h, lo, depart_s, rta_s, berth_h)
    fuel = float(np.sum(_leg_fuel(x[:n], dist, fr, sea)))

    def to_s(h: np.ndarray) -> tuple[float, ...]:
        return tuple(float(depart_s + 3600.0 * v) for v in h)

    return Schedule(to_s(arr_h), to_s(start_h), to_s(dep_h),
                    tuple(float(3600.0 * v) for v in x[:n]), not reasons, tuple(reasons), fuel)


def _leg_fuel(t_h: np.ndarray, dist_m: np.ndarray, fr: FuelRate, sea: np.ndarray) -> np.ndarray:
    """Fuel per leg [t] at steady speed (canal legs: 0, their time is fixed)."""
    v = dist_m / np.maximum(t_h * 3600.0, 1.0)
    return np.where(sea, t_h * fr.rate(v), 0.0)


def _leg_fuel_slope(t_h: np.ndarray, dist_m: np.ndarray, fr: FuelRate,
                    sea: np.ndarray) -> np.ndarray:
    """dF/dT per leg [t/h]: r(v) - v r'(v) (negative: more time, less fuel)."""
    v = dist_m / np.maximum(t_h * 3600.0, 1.0)
    return np.where(sea, fr.rate(v) - v * fr.rate_slope(v), 0.0)


def _start_times(lo: np.ndarray, hi: np.ndarray, total_h: float) -> np.ndarray:
    """Initial sail times: the shortest ones stretched in proportion towards `total_h`."""
    if lo.sum() >= total_h:
        return lo.copy()
    w = (total_h - lo.sum()) / max(float((hi - lo).sum()), 1e-9)
    return lo + (hi - lo) * min(w, 1.0)


def _reasons(legs: Sequence[LegSpec], arr_h: np.ndarray, start_h: np.ndarray, lo: np.ndarray,
             depart_s: float, rta_s: float, berth_h: np.ndarray) -> list[str]:
    """Why the schedule misses a window or the RTA (empty when it meets them all)."""
    out: list[str] = []
    tol_h = 60.0 / 3600.0
    total_h = (rta_s - depart_s) / 3600.0
    if berth_h.sum() >= total_h:
        out.append(f"berth times ({berth_h.sum():.1f} h) are longer than the time to the RTA "
                   f"({total_h:.1f} h)")
    for i, a in enumerate(legs):
        for b in legs[i + 1:]:
            if a.earliest_s is not None and b.latest_s is not None and b.latest_s < a.earliest_s:
                out.append(f"port calls in an impossible order: {b.name}'s latest arrival "
                           f"{iso(b.latest_s)} is before {a.name}'s earliest {iso(a.earliest_s)}")
    fastest = np.cumsum(lo) + np.concatenate([[0.0], np.cumsum(berth_h)[:-1]])
    for k, leg in enumerate(legs):
        t_arr = depart_s + 3600.0 * arr_h[k]
        limit = rta_s if k == len(legs) - 1 else leg.latest_s
        if leg.latest_s is not None and limit is not None:
            limit = min(limit, leg.latest_s)
        if limit is not None and t_arr > limit + 3600.0 * tol_h:
            what = "the RTA" if k == len(legs) - 1 and limit == rta_s else "its latest arrival"
            out.append(f"{leg.name}: arrival {iso(t_arr)} misses {what} {iso(limit)} by "
                       f"{(t_arr - limit) / 3600.0:.1f} h (at full speed the earliest arrival "
                       f"is {iso(depart_s + 3600.0 * fastest[k])})")
        if leg.earliest_s is not None and depart_s + 3600.0 * start_h[k] < leg.earliest_s - 60.0:
            out.append(f"{leg.name}: berth at {iso(depart_s + 3600.0 * start_h[k])} before its "
                       f"earliest arrival {iso(leg.earliest_s)}")
    return list(dict.fromkeys(out))


def describe(legs: Sequence[LegSpec], sched: Schedule) -> list[dict]:
    """Per-port rows for a plan's `extra['port_calls']` (times ISO UTC, hours)."""
    rows = []
    for leg, a, s, d, t in zip(legs, sched.arrival_s, sched.berth_start_s, sched.departure_s,
                               sched.sail_s, strict=True):
        rows.append({"port": leg.name, "arrival": iso(a), "berth_start": iso(s),
                     "departure": iso(d), "sail_h": round(t / 3600.0, 2),
                     "earliest": iso(leg.earliest_s) if leg.earliest_s is not None else "",
                     "latest": iso(leg.latest_s) if leg.latest_s is not None else "",
                     "berth_h": round(leg.berth_s / 3600.0, 2)})
    return rows

