"""Risk measures against brute-force definitions, and the refusals of bad risk settings."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from shiproute_planner.errors import ParameterError
from shiproute_planner.route.risk import cvar, parse_risk, risk_value, weighted_quantile


def test_cvar_of_equal_members_is_the_mean_of_the_worst_tail():
    rng = np.random.default_rng(3)
    v = rng.normal(500.0, 20.0, (20, 7))
    w = np.full(20, 1 / 20)
    # 20 equal members: CVaR_0.9 is the mean of the two largest, CVaR_0.75 of the five largest
    assert np.allclose(cvar(v, w, 0.9), np.sort(v, axis=0)[-2:].mean(axis=0))
    assert np.allclose(cvar(v, w, 0.75), np.sort(v, axis=0)[-5:].mean(axis=0))
    assert np.allclose(risk_value(v, w, parse_risk("worst")), v.max(axis=0))
    assert np.allclose(risk_value(v, w, parse_risk("mean")), v.mean(axis=0))


def test_weighted_cvar_splits_the_member_at_the_boundary():
    # by the definition: CVaR_a = (1 / (1 - a)) x integral over u in (a, 1) of the u-quantile
    v = np.array([[10.0], [20.0], [40.0]])
    w = np.array([0.5, 0.3, 0.2])
    # tail 0.25: 0.2 of 40 and 0.05 of 20
    assert cvar(v, w, 0.75)[0] == pytest.approx((0.2 * 40 + 0.05 * 20) / 0.25)
    u = (np.arange(100_000) + 0.5) / 100_000
    q = np.array([10.0, 20.0, 40.0])[np.searchsorted(np.cumsum(w), u)]
    assert cvar(v, w, 0.75)[0] == pytest.approx(q[u > 0.75].mean(), rel=1e-4)


def test_weighted_quantile_is_the_inverse_step_distribution():
    v = np.array([[3.0, 1.0], [1.0, 2.0], [2.0, 3.0], [4.0, 4.0]])
    w = np.full(4, 0.25)
    assert weighted_quantile(v, w, 0.5).tolist() == [2.0, 2.0]
    assert weighted_quantile(v, w, 0.9).tolist() == [4.0, 4.0]
    assert weighted_quantile(v, w, 0.1).tolist() == [1.0, 1.0]
    # brute force over every ordering of 4 values
    for perm in itertools.permutations([5.0, 6.0, 7.0, 8.0]):
        col = np.array(perm)[:, None]
        assert weighted_quantile(col, w, 0.75)[0] == 7.0


@pytest.mark.parametrize("text, words", [
    ("median", "unknown"), ("cvar:0", "strictly between 0 and 1"),
    ("cvar:1", "strictly between 0 and 1"), ("cvar:1.5", "strictly between"),
    ("cvar:-0.2", "strictly between"), ("cvar:abc", "not a number"),
    ("worst:0.9", "only cvar takes a level")])
def test_bad_risk_measures_are_refused_with_the_reason(text, words):
    with pytest.raises(ParameterError, match=words):
        parse_risk(text)


@pytest.mark.parametrize("p", [-0.1, 1.5, float("nan"), float("inf")])
def test_probabilities_outside_0_1_are_refused(p):
    with pytest.raises(ParameterError, match=r"p_hs_max must be a probability in 0\.\.1"):
        parse_risk("mean", p_hs_max=p)
    with pytest.raises(ParameterError, match="p_late_max must be a probability"):
        parse_risk("cvar:0.9", p_late_max=p)


def test_labels_round_trip():
    assert parse_risk("CVaR:0.95").label == "cvar:0.95"
    assert parse_risk("cvar").alpha == 0.9
    assert parse_risk(" worst ").label == "worst"
