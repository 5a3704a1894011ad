"""A re-plan that never silently gets worse: the previous plan's remaining stages, sailed
exactly (same waypoints, same RPM per leg) on the new forecast from the ship's position and
time, are finished like any plan and published instead of the new search's result when that
result is infeasible or worse on the objective while the carried-over plan is feasible.

The remainder is cut into the parts the planner itself sails (departure approach, optimised
span, strait passage, canal, arrival approach) so that its feasibility is judged by the same
rules as a new plan's: flags of an optimised span or a canal decide, those of computed
passages and approaches inform, and the route check at full resolution has the last word.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from shiproute_core.flags import FLAG_RTA
from shiproute_core.geodesy import unwrap_near
from shiproute_core.units import M_PER_NM

from .objectives import objective_block
from .plan_legs import LegRun
from .plan_prepare import PreparedVoyage
from .plan_types import RoutePlan
from .replan_retime import retimed_legs
from .request import PlanOptions
from .route.evaluation import RouteEvaluation
from .route.evaluation_join import joined
from .route.problem import RouteProblem
from .route.sail_fixed_point import sail_track

PASSAGE_WINDOW_S = 30 * 86400.0  # a fixed part has no RTA of its own (the plan's deadline
# is checked when the legs are assembled)
SAME_DEPARTURE_S = 60.0  # the same departure (a re-plan at the port) or RTA within this
OBJECTIVE_EPS = 1e-6  # relative: a new plan this close to the carried one is not "worse"
FEW_GENERATIONS = 20  # a wall-time search shorter than this is stated in the plan
RUN_OWN_WORDS = ("re-plan:", "re-timed:", "not re-timed:")  # the new search's, not the kept
# plan's


@dataclass(frozen=True)
class Remainder:
    """The previous plan from the ship onwards: nodes (continuous longitudes), POSIX time of
    the start, RPM per leg and the previous plan's index of each node (-1: the position)."""

    lon_deg: np.ndarray
    lat_deg: np.ndarray
    rpm: np.ndarray
    start_s: float
    prev_index: np.ndarray
    ports: tuple[str, ...]  # port name of each node ("" where none)
    planned_s: np.ndarray  # the previous plan's time at each node (the ship's time first)


def remainder_of(previous: RoutePlan, position: tuple[float, float, float] | None,
                 depart_s: float) -> Remainder | str:
    """What is left of `previous` for a ship at `position` (lat, lon, time), or from its
    departure when re-planned at the port; a sentence why not when nothing is left."""
    lon, lat, t = previous.track()
    rpm = previous.leg_rpm()
    names = tuple(w.port for w in previous.waypoints)
    if position is None:
        if abs(previous.departure_s - depart_s) > SAME_DEPARTURE_S:
            return "the previous plan left at another time"
        idx = np.arange(lon.size)
        return Remainder(lon.copy(), lat.copy(), rpm.copy(), float(t[0]), idx, names,
                         np.asarray(t, dtype=float).copy())
    now_lat, now_lon, now_s = position
    later = np.flatnonzero(t > now_s)
    if later.size == 0 or int(later[0]) == 0:
        return "the ship is not on the previous plan's time span"
    first = int(later[0])
    out_lon = np.unwrap(np.concatenate([[now_lon], unwrap_near(lon[first:], now_lon)]),
                        period=360.0)
    out_lat = np.concatenate([[now_lat], lat[first:]])
    idx = np.concatenate([[-1], np.arange(first, lon.size)])
    return Remainder(out_lon, out_lat, rpm[first - 1:].astype(float), float(now_s), idx,
                     ("", *names[first:]), np.concatenate([[now_s], t[first:]]))


def _local(rem: Remainder, prev_i: int) -> int:
    """Node of the remainder that was node `prev_i` of the previous plan (0 if behind)."""
    if rem.prev_index[0] < 0 and prev_i < rem.prev_index[1]:
        return 0  # behind the ship: the remainder starts at its position
    hit = np.flatnonzero(rem.prev_index >= prev_i)
    return int(hit[0]) if hit.size else len(rem.prev_index) - 1


def leg_ends(rem: Remainder, prep: PreparedVoyage) -> list[int] | str:
    """The remainder's node where each of the voyage's legs ends (gates, vias and the
    destination are named on the previous plan's nodes), or why the legs do not match."""
    ends, j = [], 1
    for port in prep.ports[1:]:
        found = [k for k in range(j, len(rem.ports)) if rem.ports[k] == port.name]
        if not found:
            return f"its nodes do not pass {port.name} of this voyage"
        ends.append(found[0])
        j = found[0] + 1
    if ends[-1] != len(rem.ports) - 1:
        return "it ends elsewhere than this voyage"
    return ends


def _spans_in(spans: tuple[tuple[int, int], ...], rem: Remainder, s: int, e: int
              ) -> list[tuple[int, int]]:
    """Every previous span (a, b) ending within remainder nodes (s, e], as local nodes, in
    sailing order: a leg of this voyage may hold several of the previous plan's spans (a
    strait the previous plan passed between two spans that this voyage's leg does not
    split at)."""
    out: list[tuple[int, int]] = []
    for a, b in sorted(spans):
        la, lb = max(_local(rem, a), s), _local(rem, b)
        if s <= la < lb <= e and rem.prev_index[lb] == b and (not out or la >= out[-1][1]):
            out.append((la, lb))
    return out


Part = tuple[int, int, str]  # (first node, last node, kind: pre | span | between | post | fixed)
DECIDING = "span"  # the kind whose land test decides (an optimised span)
BETWEEN = "between"  # a computed passage between two optimised spans of one leg (informs)


def leg_parts(rem: Remainder, previous: RoutePlan, prep: PreparedVoyage, k: int, s: int,
              e: int) -> list[Part] | str:
    """The parts of leg `k` (remainder nodes s..e) as the planner sails them."""
    if k in prep.strait_legs:
        return [(s, e, "fixed")]
    spans = (tuple(previous.extra.get("fixed_passages", ())) if k in prep.canal_legs
             else previous.optimised_spans)
    found = _spans_in(tuple(spans), rem, s, e)
    if not found:
        return f"its leg to {prep.ports[k + 1].name} has no planned span left"
    if k in prep.canal_legs:
        found = found[:1]
    kind = "fixed" if k in prep.canal_legs else DECIDING
    parts = [(s, found[0][0], "pre")] if found[0][0] > s else []
    for i, (a, b) in enumerate(found):
        if i and a > found[i - 1][1]:
            parts.append((found[i - 1][1], a, BETWEEN))
        parts.append((a, b, kind))
    if found[-1][1] < e:
        parts.append((found[-1][1], e, "post"))
    return parts


@dataclass(frozen=True)
class CarriedLegs:
    """The remainder sailed on the new forecast, leg by leg as `LegRun` keeps them."""

    results: tuple[RouteEvaluation, ...]
    sources: tuple[str, ...]
    approaches: tuple[tuple[RouteEvaluation | None, RouteEvaluation | None], ...]
    arrivals: tuple[float, ...]
    said: str = ""  # what re-timing the remainder did ("" nothing)
    retimed: bool = False  # re-timed to arrive on time (`replan_retime`)


def _sail(prep: PreparedVoyage, rem: Remainder, part: Part, t0: float) -> RouteEvaluation:
    """One part sailed exactly from `t0`: land and depth of an optimised span in the
    problem's own terms (port clearance at its ends), passages and approaches without a land
    test (the planner computes them against land; their flags inform)."""
    a, b, kind = part
    lon, lat = rem.lon_deg[a:b + 1], rem.lat_deg[a:b + 1]
    problem = RouteProblem(float(lon[0]), float(lat[0]), float(lon[-1]), float(lat[-1]), t0,
                           t0 + PASSAGE_WINDOW_S, prep.limits)
    land = prep.land if kind == DECIDING else None
    # the planned times start the fixed-point iterations: a remainder sailed on a new cycle
    # keeps most of them, so few passes settle it (from the departure alone it needs more)
    return sail_track(problem, prep.env, land, lon, lat, rem.rpm[a:b],
                      time_guess_s=rem.planned_s[a:b + 1])


def carried_legs(prep: PreparedVoyage, options: PlanOptions) -> CarriedLegs | str:
    """The previous plan's remainder sailed on this forecast in the voyage's legs (before
    the search, so its time is inside the budget), or a sentence why it cannot be."""
    previous = options.previous_plan
    if previous is None:
        return "no previous plan"
    if abs(previous.rta_s - prep.rta_s) > SAME_DEPARTURE_S or previous.objective != prep.terms.name:
        return "the previous plan aimed at another arrival time or objective"
    if any(c.berth_s > 0 or c.earliest_s is not None for c in prep.call_at.values()):
        return "port calls with berth or waiting times lie ahead"
    if prep.risk is not None or getattr(prep.env.sampler, "members", None) is not None:
        return "an ensemble forecast (the previous plan's spread is not re-evaluated)"
    rem = remainder_of(previous, options.position, prep.depart_s)
    if isinstance(rem, str):
        return rem
    lim = prep.limits
    if not (np.all(np.isfinite(rem.rpm)) and lim.rpm_min <= rem.rpm.min()
            and rem.rpm.max() <= lim.rpm_max):
        return f"its RPMs are not all within this ship's {lim.rpm_min:g}..{lim.rpm_max:g}"
    ends = leg_ends(rem, prep)
    if isinstance(ends, str):
        return ends
    results, sources, approaches, arrivals = [], [], [], []
    t, s = rem.start_s, 0
    for k, e in enumerate(ends):
        parts = leg_parts(rem, previous, prep, k, s, e)
        if isinstance(parts, str):
            return parts
        sailed: list[tuple[str, RouteEvaluation]] = []
        for part in parts:
            ev = _sail(prep, rem, part, t)
            sailed.append((part[2], ev))
            t = float(ev.eta_s[0])
        outer = {kind: ev for kind, ev in sailed if kind in ("pre", "post")}
        # every span of the leg decides (a passage between two of them informs)
        results.append(joined([(ev, kind != BETWEEN) for kind, ev in sailed
                               if kind not in ("pre", "post")]))
        sources.append("canal" if k in prep.canal_legs else "strait" if k in prep.strait_legs
                       else "previous_plan")
        approaches.append((outer.get("pre"), outer.get("post")))
        arrivals.append(t)
        s = e
    # a remainder hours early (the ship ahead of the previous plan's times) is slowed down
    timed = retimed_legs(prep, results, sources, approaches, rem.start_s,
                         "the previous plan's remainder")
    return CarriedLegs(timed.results, tuple(sources), timed.approaches, timed.arrivals,
                       timed.said, timed.retimed)


def carried_run(legs: CarriedLegs, run: LegRun) -> LegRun:
    """`run` (the new search's problems, baselines and counts) with the carried legs."""
    return dataclasses.replace(
        run, results=list(legs.results), sources=list(legs.sources),
        approaches=list(legs.approaches), arrivals=list(legs.arrivals), member_legs=[],
        baselines=list(run.baselines), problems=list(run.problems),
        warnings=[w for w in run.warnings if not w.startswith(RUN_OWN_WORDS)]
        + ([legs.said] if legs.said else []))


def objective_value(plan: RoutePlan) -> float:
    """The plan's objective as it states it (fuel t, NM, h, CO2 t or USD)."""
    block = plan.extra.get("objective", {})
    value = block.get("value") if isinstance(block, dict) else None
    return float(value) if isinstance(value, int | float) else plan.total_fuel_t


def precheck(legs: CarriedLegs, prep: PreparedVoyage) -> tuple[bool, float, float]:
    """(feasible, objective, fuel t) of the carried legs before the finished plan's checks:
    the flags of optimised spans and canals and the arrival against the RTA, as
    `assemble_plan` judges them (the route check can only add findings)."""
    flags = 0
    for ev, source in zip(legs.results, legs.sources, strict=True):
        if source != "strait":
            flags |= int(ev.flags[0]) & ~FLAG_RTA
    parts = [e for ev, (pre, post) in zip(legs.results, legs.approaches, strict=True)
             for e in (pre, ev, post) if e is not None]
    fuel = sum(float(e.fuel_t[0]) for e in parts)
    nm = sum(float(e.distance_m[0]) for e in parts) / M_PER_NM
    hours = (legs.arrivals[-1] - prep.depart_s) / 3600.0
    on_time = legs.arrivals[-1] <= prep.rta_s + prep.rta_tolerance_s
    value = float(objective_block(prep.terms, fuel, hours, nm)["value"])
    return flags == 0 and on_time, value, fuel


def kept_or_new(new: RoutePlan, carried_legs: CarriedLegs | str, prep: PreparedVoyage,
                options: PlanOptions, run: LegRun, finish: Callable[[LegRun], RoutePlan]
                ) -> RoutePlan:
    """`new`, or the previous plan carried over (finished by `finish`, with the same checks)
    when `new` is infeasible or worse on the objective and the carried plan is feasible;
    either way the plan states what the previous plan's remainder came to on this forecast
    (`extra["replan"]`)."""
    if options.previous_plan is None:
        return new
    if isinstance(carried_legs, str):
        said = f"previous plan not carried over: {carried_legs}"
        return dataclasses.replace(new, warnings=(*new.warnings, said),
                                   extra={**new.extra, "replan": {"carried": False,
                                                                  "why_not": carried_legs}})
    ok, value, fuel = precheck(carried_legs, prep)
    block = {"carried": True, "previous_remaining_objective": value,
             "previous_remaining_fuel_t": fuel, "previous_remaining_feasible": ok,
             "previous_remaining_retimed": carried_legs.retimed,
             "new_objective": objective_value(new), "new_feasible": new.feasible,
             "generations": run.generations, "kept_previous": False}

    def worse_than(value: float) -> bool:
        return objective_value(new) > value * (1.0 + OBJECTIVE_EPS)

    if not ok or (new.feasible and not worse_than(value)):
        return dataclasses.replace(new, extra={**new.extra, "replan": block})
    carried = finish(carried_run(carried_legs, run))  # the route check may still find more
    block.update(previous_remaining_feasible=carried.feasible,
                 previous_remaining_objective=objective_value(carried),
                 previous_remaining_fuel_t=carried.total_fuel_t)
    if not carried.feasible or (new.feasible and not worse_than(objective_value(carried))):
        return dataclasses.replace(new, extra={**new.extra, "replan": block})
    if not new.feasible:
        why = "; ".join(new.infeasible_reasons) or "constraints violated"
        said = (f"kept previous plan: new search ended infeasible after {run.generations} "
                f"gens ({why})")
    else:
        unit = carried.extra.get("objective", {}).get("unit", "t")
        said = (f"kept previous plan: new search ended worse after {run.generations} gens "
                f"({objective_value(new):.2f} {unit} against the previous plan's "
                f"{objective_value(carried):.2f} {unit} on this forecast)")
    return dataclasses.replace(
        carried, warnings=(*carried.warnings, said),
        extra={**carried.extra, "replan": {**block, "kept_previous": True}})


def with_search_effort(plan: RoutePlan, options: PlanOptions) -> RoutePlan:
    """The plan with a warning when its wall-time budget bought the seed GA only a few
    generations (a loaded machine, a short re-plan budget): the effort is part of what a plan
    was made with. Limits the caller set itself (generations, evaluations) are not stated."""
    if (options.method != "seed_ga" or options.max_evaluations
            or plan.generations >= min(FEW_GENERATIONS, options.max_generations)
            or not plan.optimised_spans):
        return plan
    search_s = plan.extra.get("timing_s", {}).get("search", float("nan"))
    said = (f"search: {plan.generations} generation(s), {plan.evaluations} route evaluations "
            f"in {search_s:.2f} s of a {options.budget_s:g} s budget; a longer budget (or a "
            "less loaded machine) may find a better plan")
    return dataclasses.replace(plan, warnings=(*plan.warnings, said))
