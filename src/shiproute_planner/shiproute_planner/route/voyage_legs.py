"""One leg of a voyage as the route-finding methods see it: the coastal approaches at both
ends (computed, given by the user, or kept from the previous plan under way), the RPM they
are sailed at, and the problem between their sea ends."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence

import numpy as np
from shiproute_core.geodesy import inverse, unwrap_near
from shiproute_core.units import M_PER_NM

from ..coastal_passages import approach_rules, computed_approach
from ..geo.landmask import LandMask
from ..geo.ports import Port
from ..objective_window import MARGIN, search_window_s, slowest_window_s
from ..objectives import ObjectiveTerms
from ..plan_types import RoutePlan
from ..shoal_passages import lane_shoal_limit
from ..straits import is_gate
from ..voyage.legs import sea_distance_m, turns_to_round
from ..voyage.stage_length import TARGET_STAGES, leg_stage_hours
from .approach import Approach, CoastalPassage, approach_length_m, lane_approaches, sail_approach
from .environment import Environment
from .evaluation import RouteEvaluation
from .given_approach import approaches_at
from .problem import RouteLimits, RouteProblem


@dataclasses.dataclass(frozen=True)
class LegSetup:
    """One leg as the methods see it: the problem between the approaches' sea ends, the
    sailed departure approach, the arrival approach and the approach RPM."""

    problem: RouteProblem
    pre: RouteEvaluation | None
    ap_arr: Approach | None
    rpm_ap: float
    notes: tuple[str, ...] = ()  # how the coastal passages were made (for the plan)


def leg_setup(a: Port, b: Port, env: Environment, lim: RouteLimits, land: LandMask,
              depart_s: float, rta_s: float, *, approach_nm: float = 25.0,
              approach_rpm: float | None = None, coastal_passage: bool = True,
              stage_hours: float | None = 12.0, objective: str = "fuel",
              terms: ObjectiveTerms | None = None, under_way: bool = False,
              previous_plan: RoutePlan | None = None,
              position: tuple[float, float, float] | None = None,
              given: Sequence[Approach] = (), target_stages: int = TARGET_STAGES) -> LegSetup:
    """Approaches of a leg a -> b and the problem between their sea ends (see `plan_voyage`;
    shared with the method comparison so every method solves the same problem). Under way
    the ship finishes the coastal passage it is in, if any, from where it is. `given`
    approaches (the user's coastal routes, e.g. from the ECDIS) that start at `a` or end at
    `b` replace the computed ones and are sailed as given."""
    coastal = (CoastalPassage(land, shoals=lane_shoal_limit(lim.under_keel))
               if coastal_passage else None)
    rest = rest_of_approach(previous_plan, position) if under_way else None
    kept = previous_arrival(previous_plan, b, position) if under_way else None
    ap_dep: Approach | None
    ap_arr: Approach | None
    # under way past (or off) the previous plan's departure approach, the ship needs its
    # own coastal passage from where it is (a strait it is in), as a cold plan gets
    own_dep = under_way and rest is None and coastal is not None and not is_gate(a)
    if kept is not None:  # under way to the same port: the arrival approach stays as planned
        ap_dep, ap_arr = None, kept
        if own_dep:
            ap_dep, _ = lane_approaches(a, b, approach_nm * M_PER_NM, with_dep=True,
                                        with_arr=False, coastal=coastal, dep_min_m=0.0)
    else:
        ap_dep, ap_arr = lane_approaches(
            a, b, approach_nm * M_PER_NM,
            with_dep=(not under_way or own_dep) and not is_gate(a),
            with_arr=not is_gate(b),  # gates lie in open water
            coastal=coastal, dep_min_m=0.0 if under_way else None)
    notes: list[str] = []
    if coastal is not None:  # computed on the fine grid, not the lane's cut
        rules = approach_rules(lim.under_keel)
        if rest is None and (kept is None or own_dep):
            ap_dep, said = computed_approach(ap_dep, a.name, False, rules)
            notes += said
        if kept is None:
            ap_arr, said = computed_approach(ap_arr, b.name, True, rules)
            notes += said
    if rest is not None:
        ap_dep = rest
    mine_dep, mine_arr = approaches_at(given, a, b)
    if mine_dep is not None and not under_way:
        ap_dep = mine_dep
    if mine_arr is not None:
        ap_arr = mine_arr
    rpm_ap = approach_rpm or lane_rpm(env, a, b, ap_dep, ap_arr, depart_s, rta_s, lim)
    pre = sail_approach(env, ap_dep, rpm_ap, depart_s, lim) if ap_dep else None
    t_leg = float(pre.eta_s[0]) if pre is not None else depart_s
    rta_leg = rta_s
    if ap_arr is not None:
        est = sail_approach(env, ap_arr, rpm_ap, rta_leg - 3600.0, lim)
        rta_leg -= float(est.eta_s[0] - est.time_s[0, 0])
    d_lon, d_lat = (ap_dep.lon_deg[-1], ap_dep.lat_deg[-1]) if ap_dep else (a.lon_deg, a.lat_deg)
    a_lon, a_lat = (ap_arr.lon_deg[0], ap_arr.lat_deg[0]) if ap_arr else (b.lon_deg, b.lat_deg)
    rta_leg = max(rta_leg, t_leg + 60.0)
    gc_m = float(inverse(d_lon, d_lat, a_lon, a_lat)[1])
    window_s = rta_leg - t_leg
    slow_s = slowest_window_s(env.model, gc_m)
    if slow_s < window_s:  # loose even over the great circle: measured along the sea lane,
        # which round a peninsula (Peterhead -> Stornoway round Cape Wrath) is far longer
        slow_s = slowest_window_s(env.model, sea_distance_m(
            *(round(float(v), 4) for v in (d_lon, d_lat, a_lon, a_lat))))
    if slow_s < window_s:
        notes.append(early_arrival_note(a.name, b.name, window_s, slow_s))
    fits_s = min(window_s, slow_s)
    stage_h = stage_hours or leg_stage_hours(
        fits_s, turns_to_round(land, float(d_lon), float(d_lat), float(a_lon),
                               float(a_lat)), target_stages)
    span_s = search_window_s(terms, env.model, gc_m, fits_s)
    n_stages = (max(1, math.ceil(span_s / (stage_h * 3600.0)) - 1)
                if span_s < rta_leg - t_leg else 0)  # 0: the whole window
    problem = RouteProblem(float(d_lon), float(d_lat), float(a_lon), float(a_lat), t_leg,
                           rta_leg, lim, stage_s=stage_h * 3600.0, n_stages=n_stages,
                           objective=objective,
                           objective_per_t_fuel=terms.per_t_fuel if terms else 1.0,
                           objective_per_h=terms.per_h if terms else 0.0,
                           dep_name=a.name, arr_name=b.name)
    return LegSetup(problem, pre, ap_arr, float(rpm_ap), tuple(notes))


def rest_of_approach(previous: RoutePlan | None,
                      position: tuple[float, float, float] | None) -> Approach | None:
    """What is left of the previous plan's departure approach from the ship's position (lat,
    lon, time), or None when the ship is past it (or there is no previous plan)."""
    if previous is None or position is None or not previous.optimised_spans:
        return None
    lon, lat, t = previous.track()
    start = previous.optimised_spans[0][0]
    now = position[2]
    if start == 0 or now >= t[start]:
        return None
    ahead = np.flatnonzero((t > now) & (np.arange(t.size) <= start))
    p_lon = unwrap_near(position[1], float(lon[ahead[0]])) if ahead.size else position[1]
    return Approach(np.concatenate([[p_lon], lon[ahead]]),
                    np.concatenate([[position[0]], lat[ahead]]))


def previous_arrival(previous: RoutePlan | None, port: Port,
                      position: tuple[float, float, float] | None) -> Approach | None:
    """The previous plan's arrival approach when it ends at `port` and the ship (lat, lon,
    time) has not reached it yet: re-plans under way keep it instead of searching the sea lane
    and the coastal passage again from every new position (~0.2 s each)."""
    if previous is None or position is None or not previous.optimised_spans:
        return None
    lon, lat, t = previous.track()
    end = previous.optimised_spans[-1][1]
    if end >= lon.size - 1 or position[2] >= t[end]:
        return None
    if abs(lat[-1] - port.lat_deg) > 1e-6 or abs(unwrap_near(port.lon_deg, lon[-1])
                                                   - lon[-1]) > 1e-6:
        return None
    return Approach(lon[end:].copy(), lat[end:].copy())


def lane_rpm(env: Environment, a: Port, b: Port, ap_dep, ap_arr, depart_s: float,
              rta_s: float, lim: RouteLimits) -> float:
    """Approach RPM: calm water RPM of the mean speed that meets the RTA on the approaches
    plus the sea lane between their sea ends, within the engine range."""
    ends = [(a.lon_deg, a.lat_deg), (b.lon_deg, b.lat_deg)]
    if ap_dep is not None:
        ends[0] = (ap_dep.lon_deg[-1], ap_dep.lat_deg[-1])
    if ap_arr is not None:
        ends[1] = (ap_arr.lon_deg[0], ap_arr.lat_deg[0])
    # the sea lane between the approaches' ends (round the land the great circle crosses)
    length = (approach_length_m(ap_dep) + approach_length_m(ap_arr)
              + sea_distance_m(*(round(float(v), 4) for v in (*ends[0], *ends[1]))))
    speed = length / max(rta_s - depart_s, 3600.0)
    model = env.model
    if hasattr(model, "rpm_for_speed"):
        from ..ship import SeaState
        from ..ship.errors import ShipModelError

        try:
            rpm = float(model.rpm_for_speed(np.array([min(speed, 30.0)]), np.array([0.0]),
                                            SeaState.calm(1))[0])
            return float(np.clip(rpm, lim.rpm_min, lim.rpm_max))
        except (ValueError, ArithmeticError, ShipModelError):
            # outside the model's range: an RTA beyond reach is sailed at full RPM
            return lim.rpm_max if speed > 10.0 else 0.5 * (lim.rpm_min + lim.rpm_max)
    return 0.5 * (lim.rpm_min + lim.rpm_max)


def early_arrival_note(dep: str, arr: str, window_s: float, slow_s: float) -> str:
    """The plan's words for a leg whose RTA leaves more time than it takes at the lowest
    RPM: the search spans the shorter time and the ship arrives early."""
    return (f"{dep} -> {arr}: the RTA leaves {window_s / 3600.0:.1f} h for the open-sea part, "
            f"more than it takes at the engine's lowest RPM ({slow_s / 3600.0:.1f} h over "
            f"{MARGIN:g} times its sea lane in calm water): the search spans "
            f"{slow_s / 3600.0:.1f} h and the ship arrives early (wait or slow down further "
            "outside the plan)")

