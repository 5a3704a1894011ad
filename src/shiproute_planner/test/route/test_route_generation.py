"""Route encoding, generation and evaluation: physics limits and the two entry points agree."""

from __future__ import annotations

import numpy as np
import pytest
from shiproute_core.flags import FLAG_LAND, FLAG_RTA
from shiproute_core.geodesy import inverse
from shiproute_planner.plan_setup import route_limits
from shiproute_planner.route.encoding import clip_genes, gene_bounds, join_genes, split_genes
from shiproute_planner.route.generate import evaluate_genes
from shiproute_planner.route.problem import RouteProblem
from shiproute_planner.route.sail import sail_tracks

T0 = 1772560800.0  # 2026-03-03T18:00Z


def _problem(env, dep=(-150.0, 20.0), arr=(-130.0, 25.0), days=5.0, **kw):
    return RouteProblem(dep[0], dep[1], arr[0], arr[1], T0, T0 + days * 86400.0,
                        route_limits(env[1]), **kw)


def test_gene_layout_round_trip(calm_env):
    p = _problem(calm_env)
    n = p.n_stages
    assert p.n_var == 2 * n + 1 and n == 9  # ceil(120 h / 12 h) - 1
    rng = np.random.default_rng(0)
    heads = rng.uniform(0, 360, (4, n))
    rpm = rng.uniform(40, 90, (4, n + 1))
    h2, r2 = split_genes(p, join_genes(heads, rpm))
    assert np.allclose(h2, heads) and np.allclose(r2, rpm)
    lo, hi = gene_bounds(p)
    x = clip_genes(p, join_genes(heads, rpm))
    assert np.all(x >= lo - 1e-9) and np.all(x <= hi + 1e-9)


def test_calm_water_stage_geometry(calm_env, land_mask):
    # calm water: SOG = STW, COG = heading; each 12 h node lies STW * 12 h along the heading
    env = calm_env[0]
    p = _problem(calm_env)
    n = p.n_stages
    az, _ = inverse(p.dep_lon_deg, p.dep_lat_deg, p.arr_lon_deg, p.arr_lat_deg)
    x = np.concatenate([[float(az)], np.zeros(n - 1), np.full(n + 1, 60.0)])[None, :]
    ev = evaluate_genes(p, env, land_mask, x)
    legs = ev.legs
    assert np.allclose(legs["sog_m_s"], legs["stw_m_s"])
    _, d = inverse(ev.lon_deg[0, :n], ev.lat_deg[0, :n], ev.lon_deg[0, 1:n + 1],
                   ev.lat_deg[0, 1:n + 1])
    assert np.allclose(d, legs["stw_m_s"][0, :n] * p.stage_s, rtol=1e-6)
    assert ev.fuel_t[0] == pytest.approx(np.sum(legs["fuel_t_per_h"] * legs["duration_s"]) / 3600)
    assert ev.time_s[0, n] == pytest.approx(T0 + n * p.stage_s)
    assert ev.feasible[0] == (ev.eta_s[0] <= p.rta_s)


def test_both_entry_points_agree(calm_env, land_mask):
    # sailing the nodes the gene evaluation produced, at its RPMs, gives the same totals
    env = calm_env[0]
    p = _problem(calm_env)
    lo, hi = gene_bounds(p)
    rng = np.random.default_rng(1)
    x = lo + (hi - lo) * rng.random((5, p.n_var))
    x[:, 1:p.n_stages] *= 0.2
    ev = evaluate_genes(p, env, land_mask, x)
    sv = sail_tracks(p, env, land_mask, ev.lon_deg, ev.lat_deg, ev.legs["rpm"])
    assert np.allclose(sv.fuel_t, ev.fuel_t, rtol=1e-6)
    assert np.allclose(sv.eta_s, ev.eta_s, atol=1.0)
    assert np.allclose(sv.distance_m, ev.distance_m, rtol=1e-6)


def test_land_and_rta_flags(calm_env, land_mask):
    env = calm_env[0]
    # straight across Japan from the Sea of Japan to the Pacific
    p = _problem(calm_env, dep=(135.0, 38.5), arr=(142.0, 34.0), days=2.0)
    lon = np.array([[135.0, 142.0]])
    lat = np.array([[38.5, 34.0]])
    ev = sail_tracks(p, env, land_mask, lon, lat, np.array([[70.0]]))
    assert ev.flags[0] & FLAG_LAND and not ev.feasible[0]
    # 1,000 NM in one day is impossible for a 25-knot ship
    p2 = _problem(calm_env, dep=(-150.0, 20.0), arr=(-132.5, 20.0), days=1.0)
    ev2 = sail_tracks(p2, env, land_mask, np.array([[-150.0, -132.5]]), np.array([[20.0, 20.0]]),
                      np.array([[p2.limits.rpm_max]]))
    assert ev2.flags[0] & FLAG_RTA and ev2.violation[0] > 0
