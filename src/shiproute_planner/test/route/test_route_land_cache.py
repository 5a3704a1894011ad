"""The GA's land count of a leg must not depend on which coastal cells earlier plans resolved
(the fine-coast cache on disk and in memory): otherwise the same voyage gets a different plan
on a fresh worker than in a process that planned others first, and fleet plans are not
reproducible. Reference: the count with every met cell resolved beforehand."""

from __future__ import annotations

import numpy as np
from shiproute_planner.geo.fine_coast import FineCoast
from shiproute_planner.geo.landmask import FINE_FACTOR
from shiproute_planner.route.fast_eval import FastEvaluator
from shiproute_planner.route.problem import RouteLimits, RouteProblem


def test_land_counts_independent_of_resolved_cells(land_mask, calm_env):
    env, _ = calm_env
    # legs across the Korea Strait and the Japanese coast: many coastal cells, some land
    rng = np.random.default_rng(7)
    n = 400
    lon0, lat0 = rng.uniform(125.0, 133.0, n), rng.uniform(31.0, 36.0, n)
    lon1, lat1 = lon0 + rng.uniform(-3.0, 3.0, n), lat0 + rng.uniform(-2.0, 2.0, n)
    problem = RouteProblem(125.0, 31.0, 133.0, 35.0, 0.0, 86400.0 * 2,
                           RouteLimits(rpm_min=40.0, rpm_max=80.0))
    saved = land_mask.__dict__.get("fine_coast")
    try:
        counts = []
        for _ in range(2):  # first: nothing resolved; second: all resolved by the first
            if not counts:
                land_mask.__dict__["fine_coast"] = FineCoast(
                    np.asarray(land_mask.raster), land_mask.cell_deg, land_mask.exact.contains,
                    FINE_FACTOR, None)
            ev = FastEvaluator(problem, env, land_mask)
            counts.append(ev.segment_land_samples(lon0, lat0, lon1, lat1))
        resolved = land_mask.__dict__["fine_coast"].keys.size
    finally:
        if saved is not None:
            land_mask.__dict__["fine_coast"] = saved
        else:
            land_mask.__dict__.pop("fine_coast", None)
    assert resolved > 100  # the legs did meet unresolved coastal cells
    assert (counts[0] > 0).sum() > 50 and (counts[0] == 0).sum() > 50
    np.testing.assert_array_equal(counts[0], counts[1])
