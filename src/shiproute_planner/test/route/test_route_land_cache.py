"""The GA's land count of a leg must not depend on which level-1 tiles earlier plans built
(the tile cache on disk and in memory): otherwise the same voyage gets a different plan on a
fresh worker than in a process that planned others first, and fleet plans are not
reproducible. Reference: the count with every met tile built beforehand."""

from __future__ import annotations

import numpy as np
from shiproute_planner.geo import fine_distance
from shiproute_planner.geo.full_land import final_land
from shiproute_planner.route.fast_eval import FastEvaluator
from shiproute_planner.route.problem import RouteLimits, RouteProblem


def test_land_counts_independent_of_built_tiles(land_mask, calm_env, monkeypatch):
    env, _ = calm_env
    # legs across the Korea Strait and the Japanese coast: many coastal tiles, some land
    rng = np.random.default_rng(7)
    n = 400
    lon0, lat0 = rng.uniform(125.0, 133.0, n), rng.uniform(31.0, 36.0, n)
    lon1, lat1 = lon0 + rng.uniform(-3.0, 3.0, n), lat0 + rng.uniform(-2.0, 2.0, n)
    problem = RouteProblem(125.0, 31.0, 133.0, 35.0, 0.0, 86400.0 * 2,
                           RouteLimits(rpm_min=40.0, rpm_max=80.0))
    final = final_land()
    fresh = fine_distance.FineDistance(final.tiles.land_near, final.contains, None)
    monkeypatch.setitem(fine_distance._DEFAULT, final.resolution, fresh)
    counts = []
    for _ in range(2):  # first: no tile built; second: all built by the first
        ev = FastEvaluator(problem, env, land_mask)
        counts.append(ev.segment_land_samples(lon0, lat0, lon1, lat1))
    assert fresh.grids.shape[0] > 20  # the legs did meet unbuilt tiles
    assert (counts[0] > 0).sum() > 50 and (counts[0] == 0).sum() > 50
    np.testing.assert_array_equal(counts[0], counts[1])
