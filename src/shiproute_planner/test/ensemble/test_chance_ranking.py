"""How the risk GA ranks candidates against chance constraints: by the sum of each bound's
excess probability first, then by the risk measure (never by lateness hours mixed with Hs
excess), with weather-decided sea-keeping a chance event and land a hard violation."""

from __future__ import annotations

import itertools

import numpy as np
from shiproute_planner.ga.ranking import deb_order
from shiproute_planner.route.member_eval import MemberOutcomes, chance_excess, risk_violation
from shiproute_planner.route.risk import RiskSpec

M = 20  # equal members: one member is a probability step of 0.05


def _outcomes(hs_members: list[int], late_members: list[int], sea_members: list[int],
              land: list[float]) -> MemberOutcomes:
    """Candidates (columns) whose first `hs_members[i]` members meet Hs above the limit, etc.;
    `land` the hard violation per candidate (the same in every member)."""
    pop = len(hs_members)

    def first(counts: list[int]) -> np.ndarray:
        return np.arange(M)[:, None] < np.array(counts)[None, :]

    zeros = np.zeros((M, pop))
    return MemberOutcomes(np.full(M, 1 / M), zeros, zeros, zeros, first(hs_members),
                          first(late_members), zeros + first(hs_members),
                          zeros + 5.0 * first(late_members),
                          np.repeat(np.array(land)[None, :], M, axis=0), first(sea_members))


def test_excess_probabilities_by_bound():
    out = _outcomes([4, 1, 0], [10, 12, 0], [3, 0, 0], [0.0, 0.0, 0.0])
    ex = chance_excess(out, RiskSpec("cvar", 0.9, p_hs_max=0.1, p_late_max=0.5))
    # 4 of 20 members over the limit against 0.1: 0.1 too many; 12 late against 0.5: 0.1
    assert np.allclose(ex["hs"], [0.1, 0.0, 0.0])
    assert np.allclose(ex["late"], [0.0, 0.1, 0.0])
    assert np.allclose(ex["sea_keeping"], [0.05, 0.0, 0.0])


def test_infeasible_candidates_rank_by_excess_then_risk_measure():
    spec = RiskSpec("cvar", 0.9, p_hs_max=0.1, p_late_max=0.5)
    # excess 0.05 at 700 t, excess 0.05 at 600 t, excess 0.10 at 500 t, feasible at 900 t
    out = _outcomes([3, 3, 4, 2], [0, 0, 0, 0], [0, 0, 0, 0], [0.0] * 4)
    risk = np.array([700.0, 600.0, 500.0, 900.0])
    v = risk_violation(out, spec, risk)
    assert v[3] == 0.0
    assert list(deb_order(v, risk)) == [3, 1, 0, 2]
    # however large or small the measure, the tie-break never outweighs one member's step
    for a, b in itertools.product([-1e12, -1.0, 0.0, 650.0, 1e12], repeat=2):
        va = risk_violation(out, spec, np.array([a, b, a, b]))
        assert va[0] < va[2] and va[1] < va[2]


def test_land_stays_hard_and_sea_keeping_within_its_bound_is_feasible():
    spec = RiskSpec("mean", p_hs_max=0.1, p_late_max=0.5)
    # 2 members with a sea-keeping limit passed (within 0.1): feasible; land: infeasible
    out = _outcomes([0, 0], [0, 0], [2, 0], [0.0, 1.5])
    v = risk_violation(out, spec, np.array([600.0, 500.0]))
    assert v[0] == 0.0 and v[1] >= 1.5
