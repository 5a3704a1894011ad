"""The GA's compiled evaluator with depth/UKC (and land) in the loop against the exact
evaluator on GA-like genes: fuel and ETA of the same genes within 0.1 %, the same depth
verdicts leg by leg."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest
from shiproute_core.flags import FLAG_DEPTH, FLAG_LAND
from shiproute_planner.depth_setup import depth_limits
from shiproute_planner.experiments.bench.planner import ga_like_population
from shiproute_planner.geo.bathymetry import default_depth_files
from shiproute_planner.plan_setup import make_environment, route_limits, to_posix_s
from shiproute_planner.route.fast_eval import fast_evaluator
from shiproute_planner.route.generate import evaluate_genes
from shiproute_planner.route.problem import RouteProblem

SKERKI = Path(__file__).parents[1] / "data" / "skerki_etopo2022_30s.nc"


def _genes(problem: RouteProblem, pop: int, rng: np.random.Generator, noise_deg: float
           ) -> np.ndarray:
    """GA-like genes (the planner bench's): great-circle headings with noise, RPMs round a
    random level."""
    return ga_like_population(problem, pop, rng, noise_deg)


def _leg_bits(ev, bit: int) -> np.ndarray:
    return (ev.leg_flags & np.uint32(bit)) != 0


@pytest.mark.skipif(not default_depth_files(), reason="ETOPO5 (ferret-datasets) not installed")
def test_fast_and_exact_agree_with_depth_and_land_in_the_loop(storm_sampler, land_mask):
    env, spec = make_environment("container_4600teu", storm_sampler)
    limits, _ = depth_limits(route_limits(spec), spec, None, True, 1.0)
    d = to_posix_s("2026-03-03T18:00Z")
    problem = RouteProblem(129.9, 34.9, -118.9, 33.4, d, d + 13 * 86400.0, limits)
    x = _genes(problem, 60, np.random.default_rng(21), 2.0)
    fast = fast_evaluator(problem, env, land_mask)
    assert fast is not None
    a, b = evaluate_genes(problem, env, land_mask, x), fast.evaluate(x)
    inside = np.abs(a.lat_deg).max(axis=1) < 70.0  # beyond the bound both are infeasible
    assert inside.sum() > 30
    # the brief's tolerance: 0.1 % of fuel and of the time under way
    assert np.max(np.abs(b.fuel_t / a.fuel_t - 1.0)[inside]) < 1e-3
    elapsed = a.eta_s - problem.depart_s
    assert np.max(np.abs(b.eta_s - a.eta_s)[inside] / elapsed[inside]) < 1e-3
    # depth: the same verdict on every leg (nodes differ by metres, not by shoals)
    assert np.array_equal(_leg_bits(a, FLAG_DEPTH)[inside], _leg_bits(b, FLAG_DEPTH)[inside])
    # land: the GA's ~1 km coastal grid may differ from the exact test on grazing legs only
    assert np.mean(_leg_bits(a, FLAG_LAND)[inside] == _leg_bits(b, FLAG_LAND)[inside]) > 0.99


def test_fast_and_exact_depth_verdicts_round_skerki_bank(calm_env):
    from shiproute_planner.geo.depth import load_bathymetry
    from shiproute_planner.route.under_keel import under_keel_for_ship

    env, spec = calm_env
    uk = under_keel_for_ship(spec, load_bathymetry([SKERKI], with_default=False))
    d = to_posix_s("2026-06-01T00:00Z")
    limits = dataclasses.replace(route_limits(spec), under_keel=uk)
    # along Skerki Bank's long axis (shoals of 11-14 m at ~37.8 N 10.9 E), 1-h stages
    problem = RouteProblem(10.42, 37.5, 11.65, 38.3, d, d + 6 * 3600.0, limits,
                           stage_s=3600.0, port_clearance_m=0.0)
    x = _genes(problem, 100, np.random.default_rng(22), 15.0)
    fast = fast_evaluator(problem, env, None)
    assert fast is not None
    a, b = evaluate_genes(problem, env, None, x), fast.evaluate(x)
    shallow = _leg_bits(a, FLAG_DEPTH)
    assert 0.05 < shallow.any(axis=1).mean() < 0.95  # routes over the bank and round it
    assert np.array_equal(shallow, _leg_bits(b, FLAG_DEPTH))
    assert np.max(np.abs(b.fuel_t / a.fuel_t - 1.0)) < 1e-3
    got, ref = b.legs["min_depth_m"], a.legs["min_depth_m"]
    both = shallow & _leg_bits(b, FLAG_DEPTH)
    assert np.allclose(got[both], ref[both], atol=1.0)  # the same shoal, metres apart
