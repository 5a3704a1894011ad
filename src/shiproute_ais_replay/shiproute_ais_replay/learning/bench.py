"""`shiproute bench learn`: records of a fouled ship -> cleaning -> learned model -> plans.

Five voyages (~17,500 one-minute records) of the container ship with +15 % frictional
resistance and 1.5 m more trim by the stern sail through the bundled March storm forecast
and are recorded as a ShipState bag with sensor faults; the bag is read, joined with the
forecast, cleaned and learned from; the last voyages are held out. Then Busan -> Long Beach is
planned with the ship file's physics model and with the learned model (same seed and budget)
and both plans are sailed by the true (fouled) ship: its fuel and lateness are reported.
"""

from __future__ import annotations

import argparse
import json
import tempfile
import time
from pathlib import Path


def evaluation_rate(models: dict, sampler, n_pop: int = 4000, repeats: int = 3) -> dict:
    """Routes per second of the GA's compiled population evaluator (no land test) for each
    model on one 13-day North Pacific problem: a learned model must cost what physics costs."""
    import numpy as np
    from shiproute_planner.route.encoding import gene_bounds
    from shiproute_planner.route.environment import Environment
    from shiproute_planner.route.fast_eval import FastEvaluator
    from shiproute_planner.route.problem import RouteLimits, RouteProblem

    out = {}
    for name, model in models.items():
        e = model.ship.engine
        problem = RouteProblem(142.8, 41.7, 239.0, 34.0, 1772582400.0, 1772582400.0 + 12 * 86400,
                               RouteLimits(rpm_min=e.rpm_min, rpm_max=e.rpm_max))
        lo, hi = gene_bounds(problem)
        x = np.random.default_rng(0).uniform(lo, hi, (n_pop, lo.size))
        ev = FastEvaluator(problem, Environment(model, sampler), None)
        ev.evaluate(x[:10])
        best = min(_timed(ev.evaluate, x) for _ in range(repeats))
        out[name] = n_pop / best
    return out


def _timed(fn, *args) -> float:
    t0 = time.perf_counter()
    fn(*args)
    return time.perf_counter() - t0


def run(voyages: int = 5, seed: int = 1, budget_s: float = 3.0) -> dict:
    """Run the benchmark; returns the JSON-able result."""
    from shiproute_planner.learned.reevaluate import reevaluate
    from shiproute_planner.learned.train import TrainConfig, train
    from shiproute_planner.planning import plan
    from shiproute_planner.request import PlanOptions, VoyageRequest, voyage_times
    from shiproute_planner.ship import load_ship
    from shiproute_weather.sampling.sampler import ForecastSampler
    from shiproute_weather.scenarios.catalogue import scenario_dataset

    from .cli import prepare
    from .synth import Corruption, HullChange, simulate_fleet_records, true_ship, write_bag

    ship = load_ship("container_4600teu")
    ds = scenario_dataset("storm_march")
    start = float(ds["time"].values[0].astype("datetime64[s]").astype(float)) + 3600.0
    change, faults = HullChange(), Corruption()
    with tempfile.TemporaryDirectory(prefix="shiproute-bench-learn-") as tmp:
        rec = simulate_fleet_records(ship, ds, voyages, start, seed=seed, change=change,
                                     corruption=faults)
        write_bag(rec, Path(tmp) / "records")
        seg, report = prepare([str(Path(tmp) / "records")], [], ship, forecasts=[ds])
        model = train(ship, seg, TrainConfig(seed=0), report)
        path = Path(tmp) / "model.nc"
        model.save(path)
        m = model.report["metrics"]
        sampler = ForecastSampler(ds)
        c = ship.condition
        mean = 0.5 * (model.reference_draft_fore_m + model.reference_draft_aft_m)
        offset = mean - faults.draft_bias_m - 0.5 * (c.draft_fore_m + c.draft_aft_m)
        _, truth = true_ship(ship, change, offset)
        from shiproute_planner.learned.select import resolve_model

        rates = evaluation_rate({"physics": resolve_model(ship, "physics")[0],
                                 "learned": resolve_model(ship, f"learned:{path}")[0]},
                                sampler)
        plans = {}
        for name, choice in (("physics", "physics"), ("learned", f"learned:{path}")):
            t0 = time.perf_counter()
            voyage = VoyageRequest("Busan", "Long Beach",
                                   *voyage_times("2026-03-04T00:00Z", "2026-03-17T00:00Z"),
                                   ship, ship_model=choice)
            p = plan(voyage, PlanOptions(budget_s=budget_s, seed=0), sampler)
            wall = time.perf_counter() - t0
            o = reevaluate(p, truth, sampler)
            plans[name] = {"planned_fuel_t": p.total_fuel_t,
                           "planned_late_h": (p.eta_s - p.rta_s) / 3600.0,
                           "true_fuel_t": o.fuel_t, "true_late_h": o.late_h,
                           "evaluations_per_s": p.evaluations / max(p.compute_time_s, 1e-9),
                           "wall_s": wall, "warnings": list(p.warnings)}
    return {
        "records": report["records_in"], "clean_segments": report["clean_segments"],
        "dropped_by_rule": report["dropped_by_rule"], "train_s": m["train_s"],
        "fuel_mre_pct": m["fuel_mre_pct"], "fuel_p95_pct": m["fuel_p95_pct"],
        "rpm_mre_pct": m["rpm_mre_pct"], "rpm_p95_pct": m["rpm_p95_pct"],
        "physics_fuel_mre_pct": m["physics_fuel_mre_pct"],
        "physics_rpm_mre_pct": m["physics_rpm_mre_pct"],
        "test_segments": m["test_segments"],
        "plan_fuel_learned_t": plans["learned"]["true_fuel_t"],
        "plan_fuel_physics_t": plans["physics"]["true_fuel_t"],
        "plan_late_learned_h": plans["learned"]["true_late_h"],
        "plan_late_physics_h": plans["physics"]["true_late_h"],
        "eval_routes_per_s_physics": rates["physics"],
        "eval_routes_per_s_learned": rates["learned"],
        "plans": plans,
    }


def main(argv: list[str]) -> int:
    """Entry point of `shiproute bench learn [--json]`."""
    ap = argparse.ArgumentParser(prog="shiproute bench learn", description=__doc__)
    ap.add_argument("--json", action="store_true", help="one JSON line")
    ap.add_argument("--voyages", type=int, default=5)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--budget", type=float, default=3.0)
    args = ap.parse_args(argv)
    out = run(args.voyages, args.seed, args.budget)
    print(json.dumps(out) if args.json else json.dumps(out, indent=2))
    return 0
