"""Equal-budget comparison on the bundled March storm: the seed GA beats unseeded NSGA-II,
SPEA2 and PSO on mean TFOC (the reference study's table 15 claim).

Voyage: 145E 36N -> 185E 42N (1,888 NM, open water, no land on the great circle), leaving
2026-03-05T18Z so the storm crosses the route, RTA at 16.5 kn average, 12 h stages (9).
Each algorithm: 5 runs (RNG seeds 0-4) of 2,000 route evaluations through the same evaluator.

Margins, from these repeated runs (5 seeds each, measured 2026-11-23 with the seed GA
defaults of commit ac01e3a): seed GA 222.0 +- 13.0 t; NSGA-II and SPEA2 239.2 +- 23.1 t
(identical: with one objective their survival orders coincide and pymoo seeds them alike);
PSO 230.6 +- 19.2 t (erratic: best single run 201 t). Observed gaps 7.2 % and 3.7 % (with
the GA defaults before that commit: 15 % and 6.1 %). The assertions ask for about 40 % of the
smaller observed gaps: 3 % over NSGA-II/SPEA2 and 1.5 % over PSO. Seeds are fixed, so the
test is deterministic; the margins say how much either side may drift before it flips.
"""

from __future__ import annotations

import numpy as np
import pytest
from shiproute_core.geodesy import inverse
from shiproute_core.units import M_S_PER_KNOT
from shiproute_planner.baselines.inputs import BaselineInputs
from shiproute_planner.baselines.metaheuristics import seed_genes
from shiproute_planner.experiments.compare import CompareSettings, repeat_runs
from shiproute_planner.route.problem import RouteLimits, RouteProblem

DEPART_S = 1_772_560_800.0 + 2 * 86400  # 2026-03-05T18:00Z
RUNS = 5
EVALUATIONS = 2000


@pytest.mark.slow
def test_seed_ga_beats_unseeded_metaheuristics_at_equal_budget(storm_sampler, land_mask) -> None:
    from shiproute_planner.plan_setup import make_environment

    env, spec = make_environment("container_4600teu", storm_sampler)
    a, b = (145.0, 36.0), (185.0, 42.0)
    _, d = inverse(*a, *b)
    rta = DEPART_S + float(d) / (16.5 * M_S_PER_KNOT)
    lim = RouteLimits(rpm_min=spec.engine.rpm_min, rpm_max=spec.engine.rpm_max)
    p = RouteProblem(*a, *b, DEPART_S, rta, lim)
    inp = BaselineInputs(p, env, land_mask)
    inp = BaselineInputs(p, env, land_mask, seed_genes=seed_genes(inp))
    rows = {r.method: r for r in repeat_runs(
        inp, ["seed_ga", "nsga2", "spea2", "pso"],
        CompareSettings(evaluations=EVALUATIONS, pop_size=50), RUNS, 0)}
    ga = rows["seed_ga"]
    assert all(ga.feasible)
    assert all(r.evaluations == EVALUATIONS for r in rows.values())
    for name, margin in (("nsga2", 0.03), ("spea2", 0.03), ("pso", 0.015)):
        other = rows[name]
        assert ga.mean_tfoc_t < (1.0 - margin) * other.mean_tfoc_t, (
            name, ga.tfoc_t, other.tfoc_t)
    assert np.isfinite(ga.std_tfoc_t)
