"""Candidates evaluated on every ensemble member, reduced by a risk measure for the GA.

`FastEvaluator.evaluate_members` sails each candidate on each member in one compiled call;
here the member rows are split into per-member outcomes (objective, fuel, ETA, the wave-limit
and lateness parts of the violation, the other weather-decided limits and everything else)
and reduced: the objective by the risk measure, Hs, sea-keeping and lateness as chance
constraints (`route.risk`), the rest (land, depth, zones, turns) as the members' weighted
mean of their violations (any member on land keeps a candidate infeasible). Each member's
fuel, ETA and objective count heave-to above the ship's wave limit and the fuel to still
meet the RTA (`route.heavy_seas`); lateness is then what even MCR cannot make up.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
from shiproute_core.flags import (
    FLAG_DECK_WETNESS,
    FLAG_ENGINE_LIMIT,
    FLAG_IMO_HIGH_WAVE_GROUP,
    FLAG_IMO_PARAMETRIC_ROLL,
    FLAG_IMO_SURF_RIDING,
    FLAG_IMO_SYNCHRONOUS_ROLL,
    FLAG_PROPELLER_EMERGENCE,
    FLAG_RTA,
    FLAG_SLAMMING,
    FLAG_WAVE_LIMIT,
    FLAG_WIND_LIMIT,
)

from .evaluation import RouteEvaluation, objective_of
from .fast_eval import FastEvaluator
from .heavy_seas import MemberVoyage, heave_to_of, member_voyage
from .problem import RouteProblem
from .risk import RiskSpec, risk_value

CHANCE_TOLERANCE = 1e-9  # probabilities equal within rounding of the weights
#: limits the weather decides member by member besides Hs: sea-keeping, wind, IMO modes
SEA_KEEPING = np.uint32(FLAG_SLAMMING | FLAG_DECK_WETNESS | FLAG_PROPELLER_EMERGENCE
                        | FLAG_WIND_LIMIT | FLAG_IMO_SURF_RIDING | FLAG_IMO_PARAMETRIC_ROLL
                        | FLAG_IMO_SYNCHRONOUS_ROLL | FLAG_IMO_HIGH_WAVE_GROUP
                        | FLAG_ENGINE_LIMIT)
TIE_SHARE = 0.25  # the risk-measure tie-break spans this share of the lightest member weight


@dataclass(frozen=True)
class MemberOutcomes:
    """Per member and candidate (M, pop): what the risk measure and chance constraints use."""

    weights: np.ndarray  # (M,), sum 1
    objective: np.ndarray
    fuel_t: np.ndarray
    eta_s: np.ndarray
    hs_exceeded: np.ndarray  # bool: Hs above the ship's limit on some leg
    late: np.ndarray  # bool: arrives after the RTA
    hs_excess: np.ndarray  # violation share of the wave limit
    late_amount: np.ndarray  # violation share of lateness
    other_violation: np.ndarray  # land, depth, zones, heading, RPM range (0 if only weather)
    sea_keeping: np.ndarray  # bool: a `SEA_KEEPING` limit exceeded on some leg
    voyage: MemberVoyage | None = None  # heave-to and RTA recovery, rows member-major

    def probability(self, event: np.ndarray) -> np.ndarray:
        """Weighted share of members where `event` (M, pop) holds."""
        return np.asarray(self.weights @ event.astype(float))


def member_outcomes(problem: RouteProblem, ev: RouteEvaluation, members: int,
                    weights: np.ndarray, fast: FastEvaluator | None = None) -> MemberOutcomes:
    """Split a member-major evaluation (M * pop rows) into per-member outcomes; with the
    evaluator `fast` (its ship model) fuel, ETA and objective count heave-to and RTA
    recovery (`route.heavy_seas`), as every plan sailed on members is judged."""
    shape = (members, -1)
    active = ev.legs["duration_s"] > 0
    limit = problem.limits.max_hs_m
    if limit is None:
        hs_excess = np.zeros(ev.fuel_t.shape)
    else:  # as `constraints.leg_flags_and_violation` counts it
        excess = np.maximum(0.0, np.nan_to_num(ev.legs["hs_m"]) - limit) / max(limit, 1e-9)
        hs_excess = np.where(active, excess, 0.0).sum(axis=1)
    late_h = np.maximum(0.0, ev.eta_s - problem.rta_s) / 3600.0
    other = np.maximum(ev.violation - hs_excess - np.where(late_h > 0, 1.0 + late_h, 0.0), 0.0)
    fuel, eta, objective, voyage = ev.fuel_t, ev.eta_s, ev.objective, None
    if fast is not None:
        voyage = member_voyage(problem, ev, heave_to_of(fast.env.model.ship))
        fuel, eta = voyage.fuel_t, voyage.eta_s
        objective = objective + (objective_of(problem, fuel, ev.distance_m, eta)
                                 - objective_of(problem, ev.fuel_t, ev.distance_m, ev.eta_s))
        late_h = np.maximum(0.0, eta - problem.rta_s) / 3600.0
    late_amount = np.where(late_h > 0, 1.0 + late_h, 0.0)
    leg_or = np.bitwise_or.reduce(ev.leg_flags, axis=1)
    # what only the weather of a member decides is a chance event, not a hard violation
    other = np.where((leg_or & ~(SEA_KEEPING | np.uint32(FLAG_WAVE_LIMIT | FLAG_RTA))) != 0,
                     other, 0.0)
    hs_hit = (leg_or & np.uint32(FLAG_WAVE_LIMIT)) != 0
    return MemberOutcomes(weights, objective.reshape(shape), fuel.reshape(shape),
                          eta.reshape(shape), hs_hit.reshape(shape),
                          (late_h > 0).reshape(shape), hs_excess.reshape(shape),
                          late_amount.reshape(shape), other.reshape(shape),
                          ((leg_or & SEA_KEEPING) != 0).reshape(shape), voyage)


def chance_excess(out: MemberOutcomes, spec: RiskSpec) -> dict[str, np.ndarray]:
    """Per chance constraint, by name, how far its probability lies above its bound (0 where
    it holds), per candidate: `hs` and `sea_keeping` (the other weather-decided limits, held
    to the same bound as Hs) against p_hs_max, `late` against p_late_max."""
    def above(event: np.ndarray, p_max: float) -> np.ndarray:
        return np.maximum(out.probability(event) - p_max - CHANCE_TOLERANCE, 0.0)

    return {"hs": above(out.hs_exceeded, spec.p_hs_max),
            "sea_keeping": above(out.sea_keeping, spec.p_hs_max),
            "late": above(out.late, spec.p_late_max)}


def risk_violation(out: MemberOutcomes, spec: RiskSpec, objective: np.ndarray) -> np.ndarray:
    """Violation per candidate: the members' mean other violation plus, when a chance
    constraint fails, the sum of the constraints' excess probabilities and a tie-break by the
    risk measure `objective` worth less than a quarter of the lightest member's weight.

    Under Deb's rules infeasible candidates are compared by violation alone: this orders
    them by how far their chance constraints are missed and, at equal excess, by their risk
    measure, so an unattainable bound never hides fuel from the search."""
    w = out.weights
    excess = np.round(sum(chance_excess(out, spec).values()), 12)
    step = TIE_SHARE * float(np.min(w[w > 0]))
    tie = step * (0.5 + np.arctan(objective) / np.pi)
    return w @ out.other_violation + np.where(excess > 0, excess + tie, 0.0)


def risk_evaluate(fast: FastEvaluator, spec: RiskSpec, x: np.ndarray) -> RouteEvaluation:
    """GA evaluation of genes `x` on every member: the objective is the risk measure of the
    members' objectives, the violation `risk_violation`; nodes and legs are member 0's."""
    return risk_evaluate_outcomes(fast, spec, x)[0]


def risk_evaluate_outcomes(fast: FastEvaluator, spec: RiskSpec, x: np.ndarray
                           ) -> tuple[RouteEvaluation, MemberOutcomes]:
    """`risk_evaluate` and the per-member outcomes it was reduced from (for the risk front)."""
    members = fast.member_count
    ev = fast.evaluate_members(x)
    weights = fast.member_weights
    out = member_outcomes(fast.problem, ev, members, weights, fast)
    pop = len(x)
    base = ev.take(np.arange(pop))
    flags = np.bitwise_or.reduce(ev.flags.reshape(members, pop), axis=0)
    objective = risk_value(out.objective, weights, spec)
    return dataclasses.replace(base, fuel_t=weights @ out.fuel_t, flags=flags,
                               violation=risk_violation(out, spec, objective),
                               objective=objective), out
