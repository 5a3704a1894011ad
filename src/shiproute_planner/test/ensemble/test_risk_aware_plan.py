"""On the ensemble storm scenario the risk-aware plan is safer and cheaper in the bad members
than the plan made on the ensemble mean alone, both sailed on the same members; bad risk
settings are refused with the reason and exit 2 from the CLI."""

from __future__ import annotations

import functools
from datetime import timedelta

import numpy as np
import pytest
from shiproute_planner.cli.plan import main as plan_main
from shiproute_planner.errors import ParameterError
from shiproute_planner.planning import plan_voyage

DEPART = "2026-03-03T18:00Z"


@functools.lru_cache(maxsize=1)
def _ensemble_sampler():
    from shiproute_weather.sampling.sampler import ForecastSampler
    from shiproute_weather.scenarios.catalogue import scenario_dataset

    return ForecastSampler(scenario_dataset("storm_march_ensemble"), dtype=np.float16)


@pytest.fixture(scope="module")
def storm_plans(land_mask):
    """(risk-aware plan, plan on the members' mean) of the 20-member storm scenario.

    cvar:0.9 weighs the worst 10 % of the members' fuel (the P90 the check compares lies at
    its edge); P(Hs > limit) <= 0.1 asks the route to keep under the ship's 8 m limit in all
    but two of the 20 members, so the P90 member is one that never heaves to; P(late) <= 0.5
    (late: a delay even MCR cannot make up) is left as loose as a coin toss so that the
    comparison is won on fuel and seas, not on lateness bought with a tighter bound."""
    sampler = _ensemble_sampler()
    kw = dict(budget_s=1e6, max_generations=25, land=land_mask, seed=0,
              default_bathymetry=True)
    risky = plan_voyage("Busan", "Long Beach", DEPART, timedelta(days=13), "container_4600teu",
                        sampler, risk="cvar:0.9", p_hs_max=0.1, p_late_max=0.5, **kw)
    mean = plan_voyage("Busan", "Long Beach", DEPART, timedelta(days=13), "container_4600teu",
                       sampler, **kw)
    return risky, mean


@pytest.mark.slow
def test_risk_aware_plan_meets_high_seas_less_often_and_states_every_missed_bound(
        storm_plans):
    """Both plans sailed on the same 20 members: the risk plan meets a sea above the limit
    less often than the mean plan and is late no more often than its bound (0.5 as given);
    a chance bound it misses is stated with achieved against asked (the search is a GA
    within a budget: a bound it does not reach must never pass in silence), one it meets
    is not; the plan says what it was made on."""
    risky, mean = storm_plans
    a, b = risky.extra["ensemble"], mean.extra["ensemble"]
    assert a["members"] == b["members"] == 20
    assert a["p_hs_violation"] < b["p_hs_violation"]
    assert a["p_late"] <= 0.5 + 1e-9
    for name, achieved, asked in (("P(Hs > limit)", a["p_hs_violation"], 0.1),
                                  ("P(late)", a["p_late"], 0.5)):
        said = [w for w in risky.warnings if f"chance constraint {name} <= {asked:g} not met"
                in w]
        assert len(said) == (1 if achieved > asked + 1e-9 else 0)
        assert all(f"not met: {achieved:.2f}" in w for w in said)
    assert risky.risk_measure == "cvar:0.9" and risky.ensemble_members == 20
    assert any("20 members" in w and "cvar:0.9" in w for w in risky.warnings)
    assert mean.risk_measure == "" and any("members' mean" in w for w in mean.warnings)
    assert not any("chance constraint" in w for w in mean.warnings)
    assert len(risky.leg_hs_spread_m) == len(risky.waypoints) - 1
    # the search saw a trade-off (the mean plan's exposure down to what it chose) and says so
    said = [w for w in risky.warnings if w.startswith("risk trade-off seen by the search")]
    assert len(said) >= 1 and f"chosen at P(Hs > limit) {a['p_hs_violation']:.2f}" in said[-1]
    assert not any("risk trade-off" in w for w in mean.warnings)


@pytest.mark.slow
def test_risk_aware_plan_has_lower_p90_fuel_and_hs_risk_than_the_mean_plan(storm_plans):
    """The issue's check 1: over the same members, P90 fuel and P(Hs > limit) both lower.

    Both plans are sailed on the members with the same heavy-seas physics (heave-to above
    the 8 m limit, then the fuel to still meet the RTA, `route.heavy_seas`), stated in both;
    the mean plan meets seas above the limit in most members and pays for it there."""
    risky, mean = storm_plans
    a, b = risky.extra["ensemble"], mean.extra["ensemble"]
    assert a["p_hs_violation"] < b["p_hs_violation"]
    assert a["fuel_t"]["p90"] < b["fuel_t"]["p90"]
    for block in (a, b):
        heavy = block["heavy_seas"]
        assert "hove to" in heavy["model"] and "propeller law" in heavy["model"]
        # a member hove to is one that meets seas above the limit, and only such a one
        assert heavy["p_heave_to"] == pytest.approx(block["p_hs_violation"])
    assert all(any("members sailed with heavy-seas physics" in w for w in p.warnings)
               for p in (risky, mean))


@pytest.mark.parametrize("extra, words", [
    (["--risk", "median"], "risk measure 'median' is unknown"),
    (["--risk", "cvar:1"], "strictly between 0 and 1"),
    (["--risk", "cvar:0"], "strictly between 0 and 1"),
    (["--risk", "mean", "--p-hs-max", "1.5"], "--p-hs-max = 1.5 is outside 0..1"),
    (["--risk", "mean", "--p-late-max", "-0.1"], "--p-late-max = -0.1 is outside 0..1"),
    (["--p-hs-max", "0.1"], "--p-hs-max needs --risk"),
])
def test_bad_risk_options_exit_2_with_the_reason(extra, words, capsys, tmp_path):
    code = plan_main(["--from", "Busan", "--to", "Long Beach", "--depart", DEPART,
                      "--rta", "13d", "--out", str(tmp_path), "--no-plot", *extra])
    assert code == 2
    err = capsys.readouterr().err
    assert words in err and "Traceback" not in err


def test_bad_risk_in_the_api_raises_parameter_error(land_mask):
    with pytest.raises(ParameterError, match="CVaR level must lie strictly between 0 and 1"):
        plan_voyage("Busan", "Long Beach", DEPART, timedelta(days=13), "container_4600teu",
                    None, risk="cvar:1.2", land=land_mask, max_generations=1)


def test_node_refuses_bad_risk_parameters():
    from shiproute_planner.voyage_params import check_parameter

    assert "unknown" in check_parameter("risk", "median")
    assert check_parameter("risk", "cvar:0.95") is None and check_parameter("risk", "") is None
    assert "outside 0..1" in check_parameter("p_hs_max", 2.0)
    assert check_parameter("p_late_max", 0.2) is None
