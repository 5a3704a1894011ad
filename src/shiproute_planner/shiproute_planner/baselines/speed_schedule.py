"""Least-fuel RPM schedule on a fixed path meeting the RTA: stage two of two-stage routing.

Dynamic programming over the path's legs with the arrival time at each waypoint as the state:
every surviving label is sailed with every RPM level in one vectorised call, labels are pruned
to a time-binned Pareto set (least fuel per arrival-time bin, nothing dominated), labels that
cannot make the RTA even at full RPM in calm water are dropped, and the least-fuel label
arriving by the RTA is traced back. With fine bins this is the exact optimum over the RPM
levels, so the two-stage rows differ from the seed GA only in how the path was found.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from shiproute_core.geodesy import inverse

from .grid_search import UNSAFE_LEG_PENALTY_T
from .labels import prune_labels
from .legs import LegSailor


@dataclass(frozen=True)
class SpeedSchedule:
    """Waypoints (possibly densified) and one RPM per leg, with the DP's own totals."""

    lon_deg: np.ndarray
    lat_deg: np.ndarray
    rpm: np.ndarray  # one per leg
    time_s: np.ndarray  # arrival time at each waypoint
    fuel_t: float
    leg_evaluations: int


def optimise_schedule(
    sailor: LegSailor,
    lon_deg: np.ndarray,
    lat_deg: np.ndarray,
    depart_s: float,
    rta_s: float,
    rpm_levels: np.ndarray,
    time_bin_s: float = 1800.0,
    max_labels: int = 400,
) -> SpeedSchedule:
    """Per-leg RPM from `rpm_levels` minimising fuel subject to arriving by `rta_s`."""
    n_legs = lon_deg.size - 1
    _, leg_m = inverse(lon_deg[:-1], lat_deg[:-1], lon_deg[1:], lat_deg[1:])
    remaining_m = np.r_[np.cumsum(np.asarray(leg_m)[::-1])[::-1], 0.0]
    fastest_m_s = float(np.max(sailor.calm_speed_m_s(rpm_levels)))
    levels = np.asarray(rpm_levels, dtype=np.float64)
    r = levels.size
    t = np.array([depart_s])
    f = np.array([0.0])
    parents: list[np.ndarray] = []
    choices: list[np.ndarray] = []
    evals = 0
    for k in range(n_legs):
        n_lab = t.size
        lab = np.repeat(np.arange(n_lab), r)
        rpm = np.tile(levels, n_lab)
        m = lab.size
        legs = sailor.between(
            np.full(m, lon_deg[k]), np.full(m, lat_deg[k]),
            np.full(m, lon_deg[k + 1]), np.full(m, lat_deg[k + 1]),
            t[lab], rpm,
        )
        evals += m
        t_new = t[lab] + legs.duration_s
        f_new = f[lab] + legs.fuel_t + np.where(legs.ok, 0.0, UNSAFE_LEG_PENALTY_T)
        # labels that cannot make the RTA even at full speed in calm water (10 % slack)
        hopeless = t_new + remaining_m[k + 1] / (1.1 * fastest_m_s) > rta_s
        if hopeless.all():
            hopeless = t_new > t_new.min()  # best effort: keep the fastest
        idx = np.flatnonzero(~hopeless)
        keep = idx[prune_labels(np.zeros(idx.size, np.int64), t_new[idx], f_new[idx], time_bin_s,
                                max_per_group=max_labels)]
        parents.append(lab[keep])
        choices.append(rpm[keep])
        t, f = t_new[keep], f_new[keep]
    on_time = np.flatnonzero(t <= rta_s)
    best = int(on_time[np.argmin(f[on_time])]) if on_time.size else int(np.argmin(t))
    fuel_total = float(f[best])
    rpm_out = np.empty(n_legs)
    i = best
    for k in range(n_legs - 1, -1, -1):
        rpm_out[k] = choices[k][i]
        i = int(parents[k][i])
    # recompute the arrival times along the chosen schedule (labels store only the last one)
    times = _trace_times(sailor, lon_deg, lat_deg, depart_s, rpm_out)
    return SpeedSchedule(lon_deg, lat_deg, rpm_out, times, fuel_total, evals)


def _trace_times(
    sailor: LegSailor, lon_deg: np.ndarray, lat_deg: np.ndarray, depart_s: float, rpm: np.ndarray
) -> np.ndarray:
    """Arrival time at each waypoint sailing the legs in order at the given RPMs."""
    times = [depart_s]
    for k in range(rpm.size):
        leg = sailor.between(
            lon_deg[k : k + 1], lat_deg[k : k + 1], lon_deg[k + 1 : k + 2], lat_deg[k + 1 : k + 2],
            np.array([times[-1]]), rpm[k : k + 1],
        )
        times.append(times[-1] + float(leg.duration_s[0]))
    return np.asarray(times)
