"""Every baseline on small voyages: feasible, off land, near the great circle in calm water,
constant RPM where the method says so, RTA met. Small grids and budgets keep it fast."""

from __future__ import annotations

import numpy as np
import pytest
from shiproute_core.geodesy import inverse
from shiproute_core.units import M_PER_NM, M_S_PER_KNOT
from shiproute_planner.baselines.ddp3 import Ddp3Config
from shiproute_planner.baselines.inputs import BaselineInputs
from shiproute_planner.baselines.isochrone import IsochroneConfig
from shiproute_planner.baselines.runners import GraphOptions, retime_path
from shiproute_planner.experiments.compare import CompareSettings, method_runner
from shiproute_planner.route.problem import RouteLimits, RouteProblem

DEPART_S = 1_772_560_800.0  # 2026-03-03T18:00Z
GRAPH = ("isochrone", "great_circle", "dijkstra", "astar", "dijkstra_rpm", "astar_rpm", "ddp3",
         "tc_astar")
META = ("seed_ga", "nsga2", "spea2", "pso", "nsga2_seeded", "spea2_seeded", "pso_seeded",
        "nsga2_2obj")
CONSTANT_RPM = ("isochrone", "great_circle", "dijkstra", "astar")

pytestmark = pytest.mark.slow  # each module fixture runs 8-16 planners (10-30 s on 2 cores)


def _settings(evaluations: int, step_deg: float, margin_deg: float, iso_step_s: float,
              stage_nm: float, lateral_nm: float) -> CompareSettings:
    return CompareSettings(
        evaluations=evaluations, pop_size=30,
        graph=GraphOptions(
            grid_step_deg=step_deg, grid_margin_deg=margin_deg, tc_astar_grid_step_deg=step_deg,
            isochrone=IsochroneConfig(step_s=iso_step_s, sector_m=lateral_nm * M_PER_NM / 3),
            ddp3=Ddp3Config(stage_m=stage_nm * M_PER_NM, lateral_m=lateral_nm * M_PER_NM,
                            n_lateral=11,
                            port_stage_m=stage_nm * M_PER_NM / 2, time_bin_s=iso_step_s / 4),
            schedule_max_leg_nm=stage_nm, schedule_bin_s=iso_step_s / 4),
    )


def _limits(env) -> RouteLimits:
    e = env[1].engine
    return RouteLimits(rpm_min=e.rpm_min, rpm_max=e.rpm_max)


def _run(inp: BaselineInputs, settings: CompareSettings, names) -> dict:
    out = {}
    for name in names:
        out[name] = method_runner(name, settings)(inp, np.random.default_rng(7))
    return out


@pytest.fixture(scope="module")
def open_ocean(calm_env, land_mask):
    """Calm water, no land near: 150E 35N -> 157E 37N (~370 NM), RTA at ~15.5 kn."""
    env, _ = calm_env
    _, d = inverse(150.0, 35.0, 157.0, 37.0)
    rta = DEPART_S + float(d) / (15.5 * M_S_PER_KNOT)
    p = RouteProblem(150.0, 35.0, 157.0, 37.0, DEPART_S, rta, _limits(calm_env), stage_s=3 * 3600)
    inp = BaselineInputs(p, env, land_mask)
    s = _settings(800, 0.2, 1.0, 1800.0, 40.0, 8.0)
    return inp, _run(inp, s, GRAPH + META), float(d)


@pytest.fixture(scope="module")
def island(calm_env, land_mask):
    """Jeju lies on the straight line 125.6E 33.4N -> 127.6E 33.4N (~100 NM)."""
    env, _ = calm_env
    p = RouteProblem(125.6, 33.4, 127.6, 33.4, DEPART_S, DEPART_S + 9 * 3600, _limits(calm_env),
                     stage_s=3600.0)
    inp = BaselineInputs(p, env, land_mask)
    s = _settings(800, 0.1, 0.6, 1800.0, 15.0, 5.0)
    return inp, _run(inp, s, GRAPH + META)


def test_island_lies_on_the_straight_line(island, land_mask) -> None:
    inp, _ = island
    p = inp.problem
    assert land_mask.segment_land_samples(np.array([p.dep_lon_deg]), np.array([p.dep_lat_deg]),
                                          np.array([p.arr_lon_deg]), np.array([p.arr_lat_deg]))[0]


@pytest.mark.parametrize("name", GRAPH + META)
def test_no_route_crosses_the_island(island, land_mask, name) -> None:
    _, results = island
    ev = results[name].evaluation
    assert int(ev.legs["land_samples"][0].sum()) == 0, name
    # and at five times finer sampling than the planner uses
    lon, lat = ev.lon_deg[0], ev.lat_deg[0]
    fine = land_mask.segment_land_samples(lon[:-1], lat[:-1], lon[1:], lat[1:], 0.01)
    # the first/last 3 km at the ports are exempt in the planner (harbour approaches)
    assert int(fine[1:-1].sum()) == 0, name


@pytest.mark.parametrize("name", GRAPH + META)
def test_each_method_is_feasible_on_open_water(open_ocean, name) -> None:
    inp, results, _ = open_ocean
    r = results[name]
    assert r.feasible, (name, r.evaluation.flags[0])
    assert r.evaluation.eta_s[0] <= inp.problem.rta_s


@pytest.mark.parametrize("name", GRAPH + META)
def test_calm_distances_within_two_percent_of_great_circle(open_ocean, name) -> None:
    _, results, gc_m = open_ocean
    dist = float(results[name].evaluation.distance_m[0])
    assert gc_m * (1 - 1e-6) <= dist <= 1.02 * gc_m, (name, dist / gc_m)


@pytest.mark.parametrize("name", CONSTANT_RPM)
def test_path_only_methods_hold_one_rpm(open_ocean, island, name) -> None:
    for _, results, *_ in (open_ocean, island):
        r = results[name]
        rpm = r.evaluation.legs["rpm"][0][r.evaluation.legs["duration_s"][0] > 0]
        assert np.ptp(rpm) == 0.0 and not r.rpm_varied, name


@pytest.fixture(scope="module")
def storm_leg(storm_sampler, land_mask):
    """Open-water leg through the March storm (150E 40N -> 168E 44N from day 4)."""
    from shiproute_planner.plan_setup import make_environment

    env, spec = make_environment("container_4600teu", storm_sampler)
    depart = DEPART_S + 4 * 86400
    _, d = inverse(150.0, 40.0, 168.0, 44.0)
    rta = depart + float(d) / (16.5 * M_S_PER_KNOT)
    lim = RouteLimits(rpm_min=spec.engine.rpm_min, rpm_max=spec.engine.rpm_max)
    p = RouteProblem(150.0, 40.0, 168.0, 44.0, depart, rta, lim, stage_s=6 * 3600)
    inp = BaselineInputs(p, env, land_mask)
    s = _settings(800, 1.0, 3.0, 3 * 3600.0, 100.0, 25.0)
    out = _run(inp, s, ("isochrone", "dijkstra", "astar", "ddp3", "seed_ga"))
    for name in ("dijkstra", "astar"):  # stage two on the very paths of stage one
        out[name + "_rpm"] = retime_path(inp, out[name], name + "_rpm", s.graph, 0.0)
    return inp, out


@pytest.mark.parametrize("name", ("dijkstra_rpm", "astar_rpm", "ddp3", "seed_ga"))
def test_speed_planning_methods_vary_rpm_in_weather(storm_leg, name) -> None:
    _, results = storm_leg
    r = results[name]
    rpm = r.evaluation.legs["rpm"][0][r.evaluation.legs["duration_s"][0] > 0]
    assert r.rpm_varied and np.ptp(rpm) > 0.2, (name, rpm)


@pytest.mark.parametrize("name", ("isochrone", "dijkstra", "astar", "dijkstra_rpm", "astar_rpm",
                                  "ddp3", "seed_ga"))
def test_all_meet_the_rta_in_weather(storm_leg, name) -> None:
    inp, results = storm_leg
    ev = results[name].evaluation
    assert ev.eta_s[0] <= inp.problem.rta_s, (name, (ev.eta_s[0] - inp.problem.rta_s) / 3600)


def test_two_stage_never_worse_than_its_path_only_stage(storm_leg) -> None:
    _, r = storm_leg
    for path_only, two in (("dijkstra", "dijkstra_rpm"), ("astar", "astar_rpm")):
        assert r[two].tfoc_t <= r[path_only].tfoc_t + 1e-6
        assert np.allclose(r[two].evaluation.lat_deg[0][[0, -1]],
                           r[path_only].evaluation.lat_deg[0][[0, -1]])
