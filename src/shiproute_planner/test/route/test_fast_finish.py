"""The fast evaluator's compiled finish (its depth scan run on the land scan's threads)
against `evaluation.finish`, the numpy reference every other evaluator uses: the same
RouteEvaluation bit for bit (flags, violations, totals, objective, leg arrays), on a real
population and on legs full of edge values."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from shiproute_planner.depth_setup import depth_limits
from shiproute_planner.experiments.bench.planner import ga_like_population
from shiproute_planner.geo.bathymetry import default_depth_files
from shiproute_planner.plan_setup import make_environment, route_limits, to_posix_s
from shiproute_planner.route.environment import PERF_FIELDS
from shiproute_planner.route.evaluation import (
    PILOTAGE_DEPTH_M,
    RouteEvaluation,
    clear_ports,
    finish,
)
from shiproute_planner.route.fast_eval import fast_evaluator
from shiproute_planner.route.fast_finish import finish_fast, port_cut_ends
from shiproute_planner.route.problem import RouteProblem

ADDED_BY_FINISH = ("land_samples", "min_depth_m", "ukc_m")


def _assert_same(a: RouteEvaluation, b: RouteEvaluation) -> None:
    """Every array of two evaluations equal in value (NaN where NaN) and dtype."""
    for f in dataclasses.fields(RouteEvaluation):
        x, y = getattr(a, f.name), getattr(b, f.name)
        if isinstance(x, dict):
            assert x.keys() == y.keys(), f.name
            for k in x:
                assert x[k].dtype == y[k].dtype, k
                assert np.array_equal(x[k], y[k], equal_nan=True), k
        else:
            assert x.dtype == y.dtype, f.name
            assert np.array_equal(x, y, equal_nan=True), f.name


def _problem(limits) -> RouteProblem:
    d = to_posix_s("2026-03-03T18:00Z")
    return RouteProblem(129.9, 34.9, -118.9, 33.4, d, d + 13 * 86400.0, limits)


def test_compiled_port_cuts_are_clear_ports():
    _, spec = make_environment("container_4600teu", None)
    p = _problem(route_limits(spec))
    rng = np.random.default_rng(3)
    lon = np.cumsum(rng.uniform(0.0, 4.0, (50, 8)), axis=1) + p.dep_lon_deg
    lat = p.dep_lat_deg + rng.normal(0.0, 2.0, (50, 8))
    lon[:, 0], lat[:, 0] = p.dep_lon_deg, p.dep_lat_deg
    lon[::2, -1], lat[::2, -1] = p.arr_lon_deg, p.arr_lat_deg
    dist = rng.uniform(0.0, 4e5, (50, 7))
    dist[0, 0], dist[1, 0], dist[2, -1] = 0.0, 0.5, np.nan  # below 1 m and unknown
    for cut in (p.port_clearance_m, 18520.0, 0.0):
        for a, b in zip(clear_ports(p, lon, lat, dist, cut), port_cut_ends(p, lon, lat, dist,
                                                                           cut), strict=True):
            assert np.array_equal(a, b, equal_nan=True)


@pytest.mark.filterwarnings("ignore:overflow encountered:RuntimeWarning")
@pytest.mark.skipif(not default_depth_files(), reason="ETOPO5 (ferret-datasets) not installed")
def test_compiled_finish_is_finish_on_edge_values():
    """Every constraint switched on, legs with NaN, inf, inactive legs, RPMs out of range,
    nodes beyond the latitude bound, legs over shelves, land and open ocean (UKC from the
    global ETOPO5 grid), late arrivals."""
    _, spec = make_environment("container_4600teu", None)
    rng = np.random.default_rng(5)
    limits, _ = depth_limits(route_limits(spec), spec, None, True, 1.0)
    limits = dataclasses.replace(
        limits, max_hs_m=6.0, max_wind_m_s=20.0, lat_bound_deg=60.0,
        imo_checks=("surf_riding", "parametric_roll", "synchronous_roll", "high_wave_group"))
    p = _problem(limits)
    pop, m = 120, 9
    legs = {k: rng.uniform(0.0, 0.3, (pop, m)) for k in PERF_FIELDS}
    for k in ("engine_limit_exceeded", "surf_riding", "parametric_roll", "synchronous_roll",
              "high_wave_group"):
        legs[k] = rng.random((pop, m)) < 0.1
    legs["hs_m"] = rng.uniform(0.0, 9.0, (pop, m))
    legs["wind_speed_m_s"] = rng.uniform(0.0, 30.0, (pop, m))
    legs["p_slamming"][rng.random((pop, m)) < 0.05] = np.nan
    legs["p_deck_wetness"][rng.random((pop, m)) < 0.05] = np.inf
    legs["hs_m"][rng.random((pop, m)) < 0.05] = np.nan
    legs["rpm"] = rng.uniform(limits.rpm_min - 5.0, limits.rpm_max + 5.0, (pop, m))
    legs["heading_deg"] = rng.uniform(0.0, 360.0, (pop, m))
    legs["turn_deg"] = rng.normal(0.0, 50.0, (pop, m))
    legs["duration_s"] = np.where(rng.random((pop, m)) < 0.1, 0.0, 43200.0)
    legs["distance_m"] = rng.uniform(0.0, 5e5, (pop, m))
    legs["fuel_t"] = rng.uniform(0.0, 50.0, (pop, m))
    lon = p.dep_lon_deg + np.cumsum(rng.uniform(0.0, 5.0, (pop, m + 1)), axis=1)
    lat = np.clip(rng.uniform(-65.0, 65.0, (pop, 1)) + np.cumsum(
        rng.normal(0.0, 2.0, (pop, m + 1)), axis=1), -80.0, 80.0)
    lon[:, 0], lat[:, 0] = p.dep_lon_deg, p.dep_lat_deg
    t = p.depart_s + np.cumsum(rng.uniform(0.0, 2.0 * 86400.0, (pop, m + 1)), axis=1)
    samples = rng.integers(0, 3, (pop, m)) * (rng.random((pop, m)) < 0.2)
    seen = []

    def scan(ends, alongside):
        seen.append(ends)
        if alongside is not None:  # the depth scan, run by the land scan's threads
            alongside(0, ends[0].size)
        return samples

    a = finish(p, None, lon, lat, t, {k: v.copy() for k, v in legs.items()}, samples)
    b = finish_fast(p, lon, lat, t, {k: v.copy() for k, v in legs.items()}, scan)
    _assert_same(a, b)
    ukc = b.legs["ukc_m"]
    assert (ukc < 0).any() and (ukc == 0).any() and np.isnan(ukc[b.legs["duration_s"] > 0]).any()
    assert (b.leg_flags == 0).any() and (b.leg_flags != 0).mean() > 0.5
    assert (b.violation == 1e12).any() and (b.violation < 1e12).any()  # inf -> 1e12
    ref = clear_ports(p, lon, lat, legs["distance_m"])
    assert all(np.array_equal(x, y) for x, y in zip(ref, seen[0], strict=True))


def test_fast_evaluation_is_finish_on_a_real_population(storm_sampler, land_mask):
    env, spec = make_environment("container_4600teu", storm_sampler)
    p = _problem(dataclasses.replace(route_limits(spec), max_hs_m=7.0))
    fast = fast_evaluator(p, env, land_mask)
    assert fast is not None
    b = fast.evaluate(ga_like_population(p, 80, np.random.default_rng(7)))
    legs = {k: v.copy() for k, v in b.legs.items() if k not in ADDED_BY_FINISH}
    a = finish(p, None, b.lon_deg, b.lat_deg, b.time_s, legs, b.legs["land_samples"])
    _assert_same(a, b)
    assert b.legs["land_samples"].any() and (b.leg_flags == 0).any()


@pytest.mark.skipif(not default_depth_files(), reason="ETOPO5 (ferret-datasets) not installed")
def test_fast_evaluation_with_ukc_is_finish_on_a_real_population(storm_sampler, land_mask):
    """The evaluator's leg arrays and port-cut ends assembled per thread
    (`_finish_kernel.assemble_and_cut`) and its land and depth verdicts: `finish` of the same
    legs, bit for bit, with the UKC constraint the planner adds by default."""
    env, spec = make_environment("container_4600teu", storm_sampler)
    limits, _ = depth_limits(route_limits(spec), spec, None, True, 1.0)
    p = _problem(limits)
    fast = fast_evaluator(p, env, land_mask)
    assert fast is not None
    b = fast.evaluate(ga_like_population(p, 90, np.random.default_rng(11)))
    legs = {k: v.copy() for k, v in b.legs.items() if k not in ADDED_BY_FINISH}
    stage = legs["duration_s"][:, :-1]
    assert (stage == p.stage_s).all()
    assert np.array_equal(legs["distance_m"][:, :-1],
                          np.maximum(b.legs["sog_m_s"][:, :-1], 0.0) * p.stage_s)
    assert np.array_equal(legs["fuel_t"], legs["fuel_t_per_h"] * legs["duration_s"] / 3600.0)
    a = finish(p, None, b.lon_deg, b.lat_deg, b.time_s, legs, b.legs["land_samples"])
    _assert_same(a, b)
    # the depth verdict is the under-keel check's own (capped) scan of the pilotage-cut legs
    active = legs["duration_s"] > 0
    ends = clear_ports(p, b.lon_deg, b.lat_deg, legs["distance_m"], PILOTAGE_DEPTH_M)
    _, ukc = limits.under_keel.leg_clearance(*ends, legs["stw_m_s"], legs["hs_m"])
    assert np.array_equal(b.legs["ukc_m"], np.where(active, ukc, np.nan), equal_nan=True)
    assert np.isfinite(b.legs["ukc_m"]).any()
