"""A plan whose constant-RPM baseline breaks a constraint says so in its warnings, so a
negative or large "saving" is not read as a comparison with a route the ship could sail."""

from __future__ import annotations

from shiproute_planner.planning import plan
from shiproute_planner.request import PlanOptions, VoyageRequest, voyage_times


def _voyage(origin: str = "Busan", destination: str = "Long Beach") -> VoyageRequest:
    depart, rta = voyage_times("2026-03-03T18:00:00Z", "2026-03-16T18:00:00Z")
    return VoyageRequest(origin, destination, depart, rta, "container_4600teu")


def _said(p) -> list[str]:
    return [w for w in p.warnings if w.startswith("baseline (") and " is infeasible (" in w]


def test_calm_open_ocean_baseline_is_feasible_and_not_flagged(land_mask):
    # Santos -> Durban: open South Atlantic, no strait, calm water, 13 days for ~4,200 NM
    options = PlanOptions(land=land_mask, budget_s=600.0, max_evaluations=300, seed=0)
    out = plan(_voyage("Santos", "Durban"), options, None)
    assert out.baseline_feasible
    assert not _said(out)


def test_storm_baseline_over_the_wave_limit_is_stated(land_mask):
    from shiproute_weather.sampling.sampler import ForecastSampler
    from shiproute_weather.scenarios.catalogue import scenario_dataset

    # cycle 2 of the March storm puts > 8 m seas on the great circle / sea lane (the demo's
    # re-plan baseline was infeasible for the Hs limit)
    out = plan(_voyage(), PlanOptions(land=land_mask, budget_s=600.0, max_evaluations=300,
                                      seed=0), ForecastSampler(scenario_dataset(
                                          "storm_march_cycle2")))
    assert not out.baseline_feasible
    said = _said(out)
    assert len(said) == 1
    assert "significant wave height above the ship limit" in said[0]
