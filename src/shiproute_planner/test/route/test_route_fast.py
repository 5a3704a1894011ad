"""The GA's compiled population evaluator against the exact evaluator and pyproj."""

from __future__ import annotations

import numpy as np
import pytest
from shiproute_core.geodesy import direct, inverse
from shiproute_planner.plan_setup import make_environment, route_limits, to_posix_s
from shiproute_planner.route import _fast_kernels as fk
from shiproute_planner.route.encoding import gene_bounds, join_genes
from shiproute_planner.route.fast_eval import fast_evaluator
from shiproute_planner.route.generate import evaluate_genes
from shiproute_planner.route.problem import RouteProblem
from shiproute_planner.route.seeding import great_circle_track


def test_rk4_geodesic_direct_matches_pyproj_to_metres():
    rng = np.random.default_rng(3)
    n = 400
    lon = rng.uniform(-180, 180, n)
    lat = rng.uniform(-65, 65, n)
    az = rng.uniform(0, 360, n)
    dist = rng.uniform(1e3, 6e5, n)  # up to a 12-h leg at 27 kn
    lon1, lat1 = np.empty(n), np.empty(n)
    fk.direct_many(lon, lat, az, dist, lon1, lat1)
    ref_lon, ref_lat = direct(lon, lat, az, dist)
    _, err = inverse(lon1, lat1, ref_lon, ref_lat)
    assert err.max() < 5.0  # metres; RK4 local error ~ R (h/R)^5 with h <= 500 km


def test_lambert_inverse_matches_pyproj():
    rng = np.random.default_rng(4)
    n = 400
    lon0, lat0 = rng.uniform(100, 250, n), rng.uniform(-60, 60, n)
    lon1, lat1 = lon0 + rng.uniform(-20, 20, n), np.clip(lat0 + rng.uniform(-15, 15, n), -70, 70)
    az, d = np.empty(n), np.empty(n)
    fk.inverse_many(lon0, lat0, lon1, lat1, az, d)
    ref_az, ref_d = inverse(lon0, lat0, lon1, lat1)
    # Lambert's formula: tens of metres over thousands of km; the auxiliary-sphere azimuth
    # differs from the geodesic one by O(f) of the longitude difference's effect
    assert np.max(np.abs(d - ref_d)) < 100.0
    assert np.max(np.abs((az - ref_az + 180) % 360 - 180)) < 0.1


@pytest.fixture(scope="module")
def storm_problem(storm_sampler):
    env, spec = make_environment("container_4600teu", storm_sampler)
    d = to_posix_s("2026-03-03T18:00Z")
    return RouteProblem(129.5, 34.8, -118.5, 33.5, d, d + 13 * 86400.0, route_limits(spec)), env


def test_fast_and_exact_evaluations_agree_on_random_populations(storm_problem, land_mask):
    problem, env = storm_problem
    lo, hi = gene_bounds(problem)
    rng = np.random.default_rng(7)
    n = problem.n_stages
    # GA-like population: great-circle headings (one per stage) with noise, random RPMs
    g_lon, g_lat = great_circle_track(problem, n + 1)
    az, _ = inverse(g_lon[:-1], g_lat[:-1], g_lon[1:], g_lat[1:])
    rpm = rng.uniform(lo[n], hi[n], (60, 1)) + rng.normal(0, 3, (60, n + 1))
    x = join_genes(np.repeat(az[None, :], 60, axis=0), np.clip(rpm, lo[n], hi[n]))
    x[:, :n] += rng.normal(0, 2.0, (60, n))
    fast = fast_evaluator(problem, env, land_mask)
    assert fast is not None
    a = evaluate_genes(problem, env, land_mask, x)
    b = fast.evaluate(x)
    inside = np.abs(a.lat_deg).max(axis=1) < 70.0  # beyond the bound both are infeasible
    assert inside.sum() > 30
    # stated tolerances: fuel 0.5 %, ETA 0.1 h, nodes 1 NM (RK4 vs Karney geodesics differ by
    # metres per leg; the weather then differs by as much as the sampled field changes)
    assert np.max(np.abs(b.fuel_t / a.fuel_t - 1)[inside]) < 5e-3
    assert np.max(np.abs(b.eta_s - a.eta_s)[inside]) < 360.0
    d_nm = np.hypot((b.lon_deg - a.lon_deg) * np.cos(np.radians(a.lat_deg)),
                    b.lat_deg - a.lat_deg) * 60.0
    assert np.max(d_nm[inside]) < 1.0
    # land verdicts: the GA decides coastal samples on a ~1 km grid, the exact test at the
    # sample itself; they may differ only for routes grazing a coast
    assert np.mean((a.flags[inside] & 1) == (b.flags[inside] & 1)) > 0.95
    assert np.mean(a.flags[inside] == b.flags[inside]) > 0.95


def test_fill_sea_matches_seastate_from_forecast(storm_sampler):
    from shiproute_planner.ship import SeaState
    from shiproute_weather.sampling.sampler_arrays import sampler_arrays

    rng = np.random.default_rng(5)
    n = 500
    lon, lat = rng.uniform(125, 245, n), rng.uniform(20, 60, n)
    t = to_posix_s("2026-03-03T18:00Z") + rng.uniform(0, 13 * 86400, n)
    sample = storm_sampler.sample(lon, lat, t)
    for key in ("sea_surface_wave_mean_period", "sea_surface_wind_wave_mean_period",
                "sea_surface_swell_wave_mean_period"):
        if key in sample:
            sample[key] = np.clip(sample[key], 0.5, 30.0)
    ref = SeaState.from_forecast(sample)
    a = sampler_arrays(storm_sampler)
    from shiproute_weather.sampling.interp_kernel import trilinear

    wx = np.empty((a.data.shape[3], n))
    trilinear(a.data, a.times_s, a.lat0_deg, a.dlat_deg, a.lon0_deg, a.dlon_deg, a.periodic,
              lon, lat, t, wx)
    chan = np.array([a.channels.get(v, -1) for v in fk.SEA_VARIABLES], dtype=np.int64)
    isdir = np.array([v in a.directions for v in fk.SEA_VARIABLES])
    sea = np.empty((10, n))
    env, _ = make_environment("container_4600teu", storm_sampler)
    fk.fill_sea(wx, chan, isdir, sea, env.model.kernel_arrays()[2])
    names = ("wind_u_m_s", "wind_v_m_s", "wind_wave_hs_m", "wind_wave_from_deg",
             "wind_wave_period_s", "swell_hs_m", "swell_from_deg", "swell_period_s",
             "current_u_m_s", "current_v_m_s")
    for i, name in enumerate(names):
        r = np.broadcast_to(getattr(ref, name), (n,))
        diff = sea[i] - r
        if name.endswith("_deg"):
            diff = (diff + 180.0) % 360.0 - 180.0
        assert np.max(np.abs(diff)) < 1e-6, name


def _brute_force_hits(land, lon0, lat0, lon1, lat1, spacing_deg):
    """Every chord point the exact scan can visit: land cells hit, coastal cells hit when the
    exact test puts the centre of the point's fine cell on land."""
    from shiproute_planner.geo.land_kernels import FINE, chord_sample, segment_ends

    out = np.zeros(lon0.size, dtype=bool)
    raster = np.asarray(land.raster)
    for s in range(lon0.size):
        ends = segment_ends(lat0[s], lon0[s], lat1[s], lon1[s])
        steps = FINE * max(1, int(np.ceil(ends[6] / spacing_deg)))
        pts = np.array([chord_sample(*ends[:6], k / steps) for k in range(steps + 1)])
        i = np.clip(((pts[:, 0] + 90.0) / land.cell_deg).astype(int), 0, raster.shape[0] - 1)
        j = np.clip((((pts[:, 1] + 180.0) % 360.0) / land.cell_deg).astype(int), 0,
                    raster.shape[1] - 1)
        v = raster[i, j]
        hit = v == 1
        coast = v == 2
        if coast.any():
            hit[coast] = land.fine_coast.contains(pts[coast, 1], pts[coast, 0])
        out[s] = hit.any()
    return out


def test_ga_land_verdict_is_the_brute_force_one_and_agrees_with_the_exact_test(land_mask):
    from shiproute_planner.route import _route_kernel as rk
    from shiproute_planner.route.fast_eval import coarse_land

    rng = np.random.default_rng(9)
    # legs of up to ~6 deg around the Tsugaru Strait, the Aleutians, the Channel Islands and
    # across the antimeridian
    centres = [(140.5, 41.5), (-175.0, 52.0), (-119.4, 33.6), (179.5, 51.5)]
    lon0, lat0, lon1, lat1 = [], [], [], []
    for c_lon, c_lat in centres:
        a = rng.uniform(-3, 3, (4, 150))
        lon0.append(c_lon + a[0])
        lat0.append(c_lat + 0.5 * a[1])
        lon1.append(c_lon + a[2])
        lat1.append(c_lat + 0.5 * a[3])
    lon0, lat0, lon1, lat1 = (np.concatenate(v) for v in (lon0, lat0, lon1, lat1))
    coarse, clear, coarse_deg = coarse_land(land_mask)
    fine = land_mask.fine_coast

    def scan(clear):
        got = np.full(lon0.size, -1, dtype=np.int64)
        todo = np.arange(lon0.size)
        rounds = 0
        while todo.size:  # as the evaluator does: resolve the cells met, rescan those legs
            missing = np.empty(64, dtype=np.int64)  # small: exercises the full-buffer path
            part = np.empty(todo.size, dtype=np.int64)
            n = rk.ga_land_hits(lon0[todo], lat0[todo], lon1[todo], lat1[todo], coarse, clear,
                                coarse_deg, np.asarray(land_mask.raster),
                                np.asarray(land_mask.coast_distance), land_mask.cell_deg,
                                0.05, fine.keys, fine.fine, missing, part)
            got[todo] = part
            fine.add(missing[:n])
            todo = todo[part < 0]
            rounds += 1
            assert rounds < 500
        return got

    got = scan(clear)
    brute = _brute_force_hits(land_mask, lon0, lat0, lon1, lat1, 0.05)
    assert 0.2 < brute.mean() < 0.9  # the sample has both kinds of legs
    assert np.array_equal(got > 0, brute)  # skipping sea never skips a land or coastal cell
    # the banded clear distances jump further than the polar-shrink ones, never onto land:
    # the same first hit and the same graded count on every leg
    assert np.array_equal(got, scan(fk.clear_distance_deg(coarse, coarse_deg)))
    assert (clear >= fk.clear_distance_deg(coarse, coarse_deg)).all()
    exact = land_mask.segment_land_samples(lon0, lat0, lon1, lat1, 0.05) > 0
    # the ~1 km grid differs from the exact test only for legs grazing a coast
    assert np.mean(exact == brute) > 0.97


def test_compiled_stage_and_polyline_eta_agree_with_the_exact_legs(storm_problem):
    from shiproute_planner.route.sail import sail_tracks

    problem, env = storm_problem
    fast = fast_evaluator(problem, env, None)
    lon, lat = great_circle_track(problem, 24)
    rpms = np.array([55.0, 65.0, 75.0, 85.0])
    exact = sail_tracks(problem, env, None, np.broadcast_to(lon, (4, lon.size)),
                        np.broadcast_to(lat, (4, lat.size)), rpms[:, None]).eta_s
    # the same legs with Lambert distances (< 100 m per leg, see above): 23 legs at >= 5 m/s
    # cannot differ by more than 23 * 100 m / 5 m/s = 460 s over the 13-day crossing
    assert np.max(np.abs(fast.polyline_eta(lon, lat, rpms) - exact)) < 460.0
    # one stage from every vertex: speed and course over ground of the exact model, and the
    # leg's end within the RK4 step's metres of pyproj's
    t = np.full(lon.size, problem.depart_s + 86400.0)
    hdg = np.linspace(0.0, 345.0, lon.size)
    rpm = np.full(lon.size, 70.0)
    sog, cog, e_lon, e_lat = fast.sail_stage(lon, lat, t, rpm, hdg, problem.stage_s)
    perf = env.perform(rpm, hdg, env.sea_state(lon, lat, t))
    assert np.allclose(sog, perf.sog_m_s, rtol=1e-3, atol=1e-3)
    assert np.max(np.abs((cog - perf.cog_deg + 180) % 360 - 180)) < 0.05
    ref_lon, ref_lat = direct(lon, lat, cog, np.maximum(sog, 0.0) * problem.stage_s)
    assert inverse(e_lon, e_lat, ref_lon, ref_lat)[1].max() < 5.0
