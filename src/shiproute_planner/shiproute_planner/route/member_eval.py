"""Candidates evaluated on every ensemble member, reduced by a risk measure for the GA.

`FastEvaluator.evaluate_members` sails each candidate on each member in one compiled call;
here the member rows are split into per-member outcomes (objective, fuel, ETA, the wave-limit
and lateness parts of the violation and everything else) and reduced: the objective by the
risk measure, the constraints as chance constraints (`route.risk`), the rest as the
members' weighted mean of their violations (any member on land keeps a candidate infeasible).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
from shiproute_core.flags import FLAG_WAVE_LIMIT

from .evaluation import RouteEvaluation
from .fast_eval import FastEvaluator
from .problem import RouteProblem
from .risk import RiskSpec, risk_value

CHANCE_TOLERANCE = 1e-9  # probabilities equal within rounding of the weights


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
    other_violation: np.ndarray  # everything else (land, depth, zones, seakeeping, ...)

    def probability(self, event: np.ndarray) -> np.ndarray:
        """Weighted share of members where `event` (M, pop) holds."""
        return np.asarray(self.weights @ event.astype(float))


def member_outcomes(problem: RouteProblem, ev: RouteEvaluation, members: int,
                    weights: np.ndarray) -> MemberOutcomes:
    """Split a member-major evaluation (M * pop rows) into per-member outcomes."""
    shape = (members, -1)
    active = ev.legs["duration_s"] > 0
    limit = problem.limits.max_hs_m
    if limit is None:
        hs_excess = np.zeros(ev.fuel_t.shape)
    else:  # as `constraints.leg_flags_and_violation` counts it
        excess = np.maximum(0.0, np.nan_to_num(ev.legs["hs_m"]) - limit) / max(limit, 1e-9)
        hs_excess = np.where(active, excess, 0.0).sum(axis=1)
    late_h = np.maximum(0.0, ev.eta_s - problem.rta_s) / 3600.0
    late_amount = np.where(late_h > 0, 1.0 + late_h, 0.0)
    other = np.maximum(ev.violation - hs_excess - late_amount, 0.0)
    hs_hit = (np.bitwise_or.reduce(ev.leg_flags & np.uint32(FLAG_WAVE_LIMIT), axis=1)) != 0
    return MemberOutcomes(weights, ev.objective.reshape(shape), ev.fuel_t.reshape(shape),
                          ev.eta_s.reshape(shape), hs_hit.reshape(shape),
                          (late_h > 0).reshape(shape), hs_excess.reshape(shape),
                          late_amount.reshape(shape), other.reshape(shape))


def _chance(p: np.ndarray, p_max: float, amount: np.ndarray) -> np.ndarray:
    """Violation of P <= p_max: the excess probability plus the members' mean amount."""
    return np.where(p > p_max + CHANCE_TOLERANCE, (p - p_max) + amount, 0.0)


def risk_violation(out: MemberOutcomes, spec: RiskSpec) -> np.ndarray:
    """Violation per candidate: mean other violation + the two chance constraints."""
    w = out.weights
    return (w @ out.other_violation
            + _chance(out.probability(out.hs_exceeded), spec.p_hs_max, w @ out.hs_excess)
            + _chance(out.probability(out.late), spec.p_late_max, w @ out.late_amount))


def risk_evaluate(fast: FastEvaluator, spec: RiskSpec, x: np.ndarray) -> RouteEvaluation:
    """GA evaluation of genes `x` on every member: the objective is the risk measure of the
    members' objectives, the violation `risk_violation`; nodes and legs are member 0's."""
    members = fast.member_count
    ev = fast.evaluate_members(x)
    weights = fast.member_weights
    out = member_outcomes(fast.problem, ev, members, weights)
    pop = len(x)
    base = ev.take(np.arange(pop))
    flags = np.bitwise_or.reduce(ev.flags.reshape(members, pop), axis=0)
    return dataclasses.replace(base, fuel_t=weights @ out.fuel_t, flags=flags,
                               violation=risk_violation(out, spec),
                               objective=risk_value(out.objective, weights, spec))
