"""Run every method on one voyage and collect comparable rows (tables 11/12 and 15 shapes).

All methods share one `BaselineInputs` (problem, environment, land, seed genes computed once),
so the only difference between rows is the route-finding method. Metaheuristics get the same
number of route evaluations; `repeat_runs` gives each of them several RNG seeds.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from shiproute_core.units import M_PER_NM, M_S_PER_KNOT

from ..baselines import runners
from ..baselines.great_circle import run_great_circle
from ..baselines.inputs import BaselineInputs
from ..baselines.metaheuristics import run_pymoo_method, run_seed_ga
from ..baselines.result import BaselineResult
from ..baselines.runners import GraphOptions, leg_rpm_varies
from ..ga.loop import GAConfig
from .outcome import MethodOutcome, RepeatRow

LABELS: dict[str, str] = {
    "isochrone": "Isochrone (path only)",
    "great_circle": "Great circle/sea lane",
    "dijkstra": "Dijkstra (path only)",
    "astar": "A* (path only)",
    "dijkstra_rpm": "Dijkstra+RPM (two stage)",
    "astar_rpm": "A*+RPM (two stage)",
    "ddp3": "3DDP (ETA-fuel Pareto)",
    "tc_astar": "Time-constr. A* (ext-nodes)",
    "nsga2": "NSGA-II",
    "spea2": "SPEA2",
    "pso": "PSO",
    "nsga2_seeded": "Seed-NSGA-II",
    "spea2_seeded": "Seed-SPEA2",
    "pso_seeded": "Seed-PSO",
    "nsga2_2obj": "NSGA-II time-fuel (2 obj)",
    "seed_ga": "Seed GA (one stage)",
}
GRAPH_ORDER = ("isochrone", "great_circle", "dijkstra", "astar", "dijkstra_rpm", "astar_rpm",
               "ddp3", "tc_astar")
META_ORDER = ("nsga2", "spea2", "pso", "nsga2_seeded", "spea2_seeded", "pso_seeded",
              "nsga2_2obj", "seed_ga")
REPEAT_ORDER = ("spea2", "pso", "nsga2", "spea2_seeded", "pso_seeded", "nsga2_seeded", "seed_ga")
TWO_STAGE = ("dijkstra_rpm", "astar_rpm")


@dataclass(frozen=True)
class CompareSettings:
    """Budgets and resolutions of one comparison."""

    evaluations: int = 6000  # route evaluations per metaheuristic run
    pop_size: int = 50
    graph: GraphOptions = GraphOptions()  # noqa: RUF009 - frozen, safe to share
    ga_config: GAConfig | None = None


def method_runner(name: str, s: CompareSettings) -> Callable[[BaselineInputs, np.random.Generator],
                                                              BaselineResult]:
    """A function (inputs, rng) -> result for method `name`."""
    g = s.graph
    graph: dict[str, Callable[[BaselineInputs], BaselineResult]] = {
        "great_circle": run_great_circle,
        "isochrone": lambda inp: runners.run_isochrone(inp, g),
        "dijkstra": lambda inp: runners.run_grid(inp, False, g),
        "astar": lambda inp: runners.run_grid(inp, True, g),
        "dijkstra_rpm": lambda inp: runners.run_two_stage(inp, False, g),
        "astar_rpm": lambda inp: runners.run_two_stage(inp, True, g),
        "ddp3": lambda inp: runners.run_ddp3(inp, g),
        "tc_astar": lambda inp: runners.run_tc_astar(inp, g),
    }
    if name in graph:
        fn = graph[name]
        return lambda inp, rng: fn(inp)
    if name == "seed_ga":
        return lambda inp, rng: run_seed_ga(inp, s.evaluations, rng, s.ga_config)
    algo = name.split("_")[0]
    seeded = name.endswith("_seeded") or name == "nsga2_2obj"
    two = name == "nsga2_2obj"
    return lambda inp, rng: run_pymoo_method(inp, algo, s.evaluations, rng, seeded, two,
                                             s.pop_size)


def outcome_of(r: BaselineResult, rta_s: float) -> MethodOutcome:
    """Comparable summary of a result (active legs only)."""
    ev = r.evaluation
    legs = ev.legs
    active = legs["duration_s"][0] > 0
    rpm = legs["rpm"][0][active]
    lon, lat = ev.lon_deg[0], ev.lat_deg[0]
    keep = np.r_[True, active]
    return MethodOutcome(
        method=r.method, label=LABELS.get(r.method, r.method), tfoc_t=float(ev.fuel_t[0]),
        distance_nm=float(ev.distance_m[0]) / M_PER_NM, eta_s=float(ev.eta_s[0]), rta_s=rta_s,
        land_crossings=int(np.count_nonzero(legs["land_samples"][0] > 0)),
        feasible=bool(ev.feasible[0]), infeasible_reasons=_reasons(int(ev.flags[0])),
        rpm_varied=r.rpm_varied and leg_rpm_varies(rpm),
        rpm_mean=float(np.average(rpm, weights=legs["duration_s"][0][active])) if rpm.size
        else float("nan"),
        compute_s=r.compute_s, route_evaluations=r.route_evaluations + r.leg_evaluations,
        track_lon_deg=lon[keep], track_lat_deg=lat[keep], leg_rpm=rpm,
        leg_sog_kn=legs["sog_m_s"][0][active] / M_S_PER_KNOT, leg_start_s=ev.time_s[0][:-1][active],
        pareto_eta_s=r.pareto_eta_s, pareto_fuel_t=r.pareto_fuel_t,
    )


def _reasons(flags: int) -> tuple[str, ...]:
    from shiproute_core.flags import describe_flags

    return tuple(describe_flags(flags))


def run_methods(inp: BaselineInputs, methods: list[str], settings: CompareSettings,
                seed: int = 0, on_done: Callable[[MethodOutcome], None] | None = None
                ) -> list[MethodOutcome]:
    """Each method once (metaheuristics with RNG seed `seed`), in the order given."""
    out = []
    for name in methods:
        rng = np.random.default_rng(seed)
        o = outcome_of(method_runner(name, settings)(inp, rng), inp.problem.rta_s)
        out.append(o)
        if on_done is not None:
            on_done(o)
    return out


def repeat_runs(inp: BaselineInputs, methods: list[str], settings: CompareSettings,
                repeats: int, first_seed: int = 0,
                on_done: Callable[[RepeatRow], None] | None = None) -> list[RepeatRow]:
    """Each metaheuristic `repeats` times with RNG seeds first_seed.. at the same budget."""
    rows = []
    for name in methods:
        fn = method_runner(name, settings)
        tfoc, feas, secs, evals = [], [], [], 0
        for k in range(repeats):
            r = fn(inp, np.random.default_rng(first_seed + k))
            tfoc.append(r.tfoc_t)
            feas.append(r.feasible)
            secs.append(r.compute_s)
            evals = max(evals, r.route_evaluations)
        row = RepeatRow(name, LABELS.get(name, name), tuple(tfoc), tuple(feas), evals,
                        float(np.mean(secs)))
        rows.append(row)
        if on_done is not None:
            on_done(row)
    return rows


def best_known_t(outcomes: list[MethodOutcome], rows: list[RepeatRow]) -> float:
    """Least feasible TFOC seen in any row or run (NaN if nothing was feasible)."""
    vals = [o.tfoc_t for o in outcomes if o.feasible]
    for r in rows:
        vals += [v for v, ok in zip(r.tfoc_t, r.feasible, strict=True) if ok]
    return float(min(vals)) if vals else float("nan")


def seed_ga_margin_pct(outcomes: list[MethodOutcome]) -> dict[str, float | str]:
    """Seed GA TFOC saving against the best feasible two-stage row [%] (positive = GA better)."""
    ga = next((o for o in outcomes if o.method == "seed_ga"), None)
    two = [o for o in outcomes if o.method in TWO_STAGE and o.feasible]
    if ga is None or not two:
        return {}
    best = min(two, key=lambda o: o.tfoc_t)
    return {"best_two_stage": best.method, "best_two_stage_tfoc_t": round(best.tfoc_t, 3),
            "seed_ga_tfoc_t": round(ga.tfoc_t, 3),
            "seed_ga_margin_pct": round(100.0 * (best.tfoc_t - ga.tfoc_t) / best.tfoc_t, 3)}
