"""The risk front keeps, per exposure, the best candidate the search saw; its Pareto front and
its choice within the bounds match a brute force over every candidate offered."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from shiproute_planner.risk_front import RiskFront, front_note
from shiproute_planner.route.member_eval import MemberOutcomes
from shiproute_planner.route.risk import RiskSpec, weighted_quantile

M = 5


def _outcomes(rng: np.random.Generator, pop: int) -> tuple[MemberOutcomes, np.ndarray]:
    """Random member outcomes of `pop` candidates on M equally weighted members, and their
    risk measure (the members' mean fuel)."""
    w = np.full(M, 1.0 / M)
    fuel = rng.uniform(400.0, 700.0, size=(M, pop))
    hs = rng.random((M, pop)) < 0.5
    late = rng.random((M, pop)) < 0.3
    other = np.where(rng.random(pop) < 0.2, 1.0, 0.0)[None, :].repeat(M, axis=0)
    zeros = np.zeros((M, pop))
    out = MemberOutcomes(w, fuel, fuel, zeros, hs, late, zeros, zeros, other, hs & late)
    return out, w @ fuel


def _brute(batches, spec: RiskSpec):
    """(Pareto front as (exposure, risk) pairs, best risk within the bounds) over every
    candidate free of other violations and on time within the bound; the exposure is the
    larger of P(Hs > limit) and P(another sea-keeping limit), both held to p_hs_max."""
    pts = []
    for out, risk in batches:
        p_hs = out.probability(out.hs_exceeded)
        p_sk = out.probability(out.sea_keeping)
        p_late = out.probability(out.late)
        for k in range(risk.size):
            if out.other_violation[0, k] == 0 and p_late[k] <= spec.p_late_max + 1e-9:
                pts.append((round(max(float(p_hs[k]), float(p_sk[k])), 9), float(risk[k])))
    front = sorted({(h, r) for h, r in pts
                    if not any((h2 <= h and r2 < r) or (h2 < h and r2 <= r) for h2, r2 in pts)})
    inside = [r for h, r in pts if h <= spec.p_hs_max + 1e-9]
    return front, (min(inside) if inside else None)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_front_and_choice_match_a_brute_force_over_every_candidate(seed):
    rng = np.random.default_rng(seed)
    spec = RiskSpec("mean", p_hs_max=0.4, p_late_max=0.4)
    front = RiskFront(spec)
    batches = []
    for _ in range(6):  # generations
        out, risk = _outcomes(rng, 40)
        front.offer(rng.random((40, 3)), out, risk)
        batches.append((out, risk))
    want_front, want_best = _brute(batches, spec)
    got = [(p.exposure, p.risk) for p in front.front()]
    assert np.allclose(np.asarray(got).reshape(-1, 2), np.asarray(want_front).reshape(-1, 2))
    # along the front, exposure rises as the risk measure falls
    assert all(a[0] < b[0] and a[1] > b[1] for a, b in itertools.pairwise(got))
    inside = front.within_bounds()
    assert (want_best is None) == (not inside)
    if inside:
        assert inside[0].risk == pytest.approx(want_best)


def test_front_point_keeps_the_genes_and_p90_of_its_candidate():
    rng = np.random.default_rng(7)
    out, risk = _outcomes(rng, 30)
    x = rng.random((30, 4))
    front = RiskFront(RiskSpec("mean", p_hs_max=1.0, p_late_max=1.0))
    front.offer(x, out, risk)
    for p in front.front():
        k = int(np.flatnonzero(np.all(x == p.genes, axis=1))[0])
        assert p.risk == pytest.approx(risk[k])
        assert p.p90_fuel_t == pytest.approx(
            weighted_quantile(out.fuel_t[:, k:k + 1], out.weights, 0.9)[0])


def test_front_note_states_the_cost_of_lower_exposure_and_the_choice():
    rng = np.random.default_rng(3)
    front = RiskFront(RiskSpec("cvar", 0.9, p_hs_max=0.2, p_late_max=1.0))
    for _ in range(4):
        out, risk = _outcomes(rng, 50)
        front.offer(rng.random((50, 2)), out, risk)
    pts = front.front()
    assert len(pts) >= 2
    note = front_note(pts, front.spec, 0.2)
    assert f"from {pts[-1].exposure:.2f} to {pts[0].exposure:.2f} costs" in note
    assert f"{pts[0].risk - pts[-1].risk:+.1f} in cvar:0.9" in note
    assert "asked P(Hs > limit) <= 0.2; chosen at P(Hs > limit) 0.20" in note
    # no front: nothing to say; one point: no trade-off, said, with what else was seen
    assert front_note([], front.spec, None) == ""
    one = front_note(pts[:1], front.spec, 0.2, pts[-1].exposure)
    assert f"none: the lowest P(Hs > limit) seen, {pts[0].exposure:.2f}, is also the best" in one
    assert f"routes seen up to {pts[-1].exposure:.2f} cost more" in one
    only = front_note(pts[:1], front.spec, 0.2, pts[0].exposure)
    assert f"none: every route seen had P(Hs > limit) {pts[0].exposure:.2f}" in only
