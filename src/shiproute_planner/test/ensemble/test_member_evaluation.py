"""Members are kept through evaluation: the compiled member-axis evaluation against the
single-forecast evaluators applied member by member, and a one-member ensemble against the
deterministic forecast."""

from __future__ import annotations

from datetime import timedelta

import numpy as np
import pytest
from shiproute_core.geodesy import inverse
from shiproute_planner.plan_setup import make_environment, route_limits, to_posix_s
from shiproute_planner.planning import plan_voyage
from shiproute_planner.route.encoding import gene_bounds, join_genes
from shiproute_planner.route.fast_eval import fast_evaluator
from shiproute_planner.route.generate import evaluate_genes
from shiproute_planner.route.problem import RouteProblem
from shiproute_planner.route.seeding import great_circle_track
from shiproute_weather.sampling.sampler import ForecastSampler

DEPART = "2026-03-03T18:00Z"


def _problem_and_genes(sampler, pop: int = 24):
    env, spec = make_environment("container_4600teu", sampler)
    d = to_posix_s(DEPART)
    problem = RouteProblem(129.5, 34.8, -118.5, 33.5, d, d + 13 * 86400.0, route_limits(spec))
    lo, hi = gene_bounds(problem)
    n = problem.n_stages
    rng = np.random.default_rng(11)
    g_lon, g_lat = great_circle_track(problem, n + 1)
    az, _ = inverse(g_lon[:-1], g_lat[:-1], g_lon[1:], g_lat[1:])
    rpm = rng.uniform(lo[n], hi[n], (pop, 1)) + rng.normal(0, 2, (pop, n + 1))
    x = join_genes(np.repeat(az[None, :], pop, axis=0), np.clip(rpm, lo[n], hi[n]))
    x[:, :n] += rng.normal(0, 1.5, (pop, n))
    return problem, env, x


def test_two_members_with_different_winds_give_two_different_evaluations(two_members,
                                                                           land_mask):
    sampler = ForecastSampler(two_members, member_dtype=np.float32)
    assert sampler.members is not None and sampler.members.count == 2
    problem, env, x = _problem_and_genes(sampler)
    fast = fast_evaluator(problem, env, land_mask)
    ev = fast.evaluate_members(x)
    pop = len(x)
    n = problem.n_stages
    sog = ev.legs["sog_m_s"].reshape(2, pop, -1)[:, :, :n]
    rate = ev.legs["fuel_t_per_h"].reshape(2, pop, -1)[:, :, :n]
    assert not np.array_equal(ev.fuel_t[:pop], ev.fuel_t[pop:])
    # the same genes eastbound (headings 45..135 deg): a 5 m/s following wind and 1.5 m sea
    # against an 18 m/s head wind and 5 m head sea; at the same RPM the ship makes less speed
    # over ground and, with the added resistance loading the propeller, burns more per hour
    hs = ev.legs["hs_m"].reshape(2, pop, -1)[:, :, :n]
    inside = (hs[0] > 0) & (hs[1] > 0)  # legs past the grid's east edge meet no forecast
    assert inside.mean() > 0.8
    assert np.all(sog[1][inside] < sog[0][inside])
    assert np.all(rate[1][inside] > rate[0][inside])
    assert np.allclose(hs[0][inside], 1.5, atol=0.01)
    assert np.allclose(hs[1][inside], 5.0, atol=0.01)


def test_member_axis_equals_the_single_forecast_evaluators_member_by_member(two_members,
                                                                            land_mask):
    sampler = ForecastSampler(two_members, member_dtype=np.float32)
    problem, env, x = _problem_and_genes(sampler)
    fast = fast_evaluator(problem, env, land_mask)
    ev = fast.evaluate_members(x)
    pop = len(x)
    for k in range(2):
        one = ForecastSampler(two_members.isel(member=k))  # a deterministic forecast
        _, env_k, _ = _problem_and_genes(one)
        ref = fast_evaluator(problem, env_k, land_mask).evaluate(x)
        rows = slice(k * pop, (k + 1) * pop)
        # the same compiled model on the same fields: identical to the last bit
        assert np.array_equal(ev.fuel_t[rows], ref.fuel_t)
        assert np.array_equal(ev.eta_s[rows], ref.eta_s)
        assert np.array_equal(ev.lon_deg[rows], ref.lon_deg)
        assert np.array_equal(ev.violation[rows], ref.violation)
        # the exact evaluator (pyproj geodesics, Python loop over stages) on member k alone,
        # within the fast-vs-exact tolerances of test_route_fast (fuel 0.5 %; ETA 0.1 h on a
        # 13-day voyage, here 0.1 % of the time under way: random RPMs make some far longer)
        exact = evaluate_genes(problem, env_k, land_mask, x[:6])
        assert np.max(np.abs(ev.fuel_t[rows][:6] / exact.fuel_t - 1)) < 5e-3
        under_way = exact.eta_s - problem.depart_s
        assert np.max(np.abs(ev.eta_s[rows][:6] - exact.eta_s) / under_way) < 1e-3


def test_sampler_view_of_an_ensemble_is_the_weighted_member_mean(two_members):
    sampler = ForecastSampler(two_members)
    got = sampler.sample(np.array([180.0]), np.array([40.0]),
                         np.array([to_posix_s("2026-03-05T00:00Z")]))
    assert got["eastward_wind"][0] == pytest.approx((5.0 - 18.0) / 2, abs=1e-4)
    assert got["sea_surface_wave_significant_height"][0] == pytest.approx(3.25, abs=1e-4)
    weighted = two_members.assign_coords(member_weight=("member", [3.0, 1.0]))
    got = ForecastSampler(weighted).sample(np.array([180.0]), np.array([40.0]),
                                           np.array([to_posix_s("2026-03-05T00:00Z")]))
    assert got["eastward_wind"][0] == pytest.approx(0.75 * 5.0 - 0.25 * 18.0, abs=1e-4)


def test_one_member_ensemble_gives_exactly_the_deterministic_plan(two_members, land_mask):
    one = two_members.isel(member=[1])  # keeps the member dimension, size 1
    det = two_members.isel(member=1, drop=True)
    kw = dict(budget_s=1e6, max_generations=3, land=land_mask, seed=4)  # no wall-time cut
    a = plan_voyage("Busan", "Long Beach", DEPART, timedelta(days=13), "container_4600teu",
                    one, risk="cvar:0.9", **kw)
    b = plan_voyage("Busan", "Long Beach", DEPART, timedelta(days=13), "container_4600teu",
                    det, **kw)
    wa = np.array([(w.lat_deg, w.lon_deg, w.heading_deg, w.shaft_rpm) for w in a.waypoints])
    wb = np.array([(w.lat_deg, w.lon_deg, w.heading_deg, w.shaft_rpm) for w in b.waypoints])
    assert np.array_equal(wa, wb, equal_nan=True)
    assert a.total_fuel_t == b.total_fuel_t and a.eta_s == b.eta_s
    assert a.extra["ensemble"]["members"] == 1  # and the plan says what it was made on
    # whatever the winning route (GA genes or a baseline track), its one member sails it on
    # the deterministic forecast (kept in half precision): the plan's own fuel and ETA
    block = a.extra["ensemble"]
    assert block["fuel_t"]["p50"] == pytest.approx(a.total_fuel_t, rel=2e-3)
    assert block["eta_s"]["p50"] == pytest.approx(a.eta_s, abs=600.0)
