"""A voyage through narrow water at the default clearance (0.5 NM near the span ends and in
narrow water, 2 NM in open sea): Busan -> Yokohama goes through the Kanmon Strait and the
Seto Inland Sea, as the sea lane does, not round Kyushu (over 120 NM longer), and its plan is
feasible."""

from __future__ import annotations

import numpy as np
import pyproj
from shiproute_planner.plan_request import build_request, run_request


def test_busan_yokohama_goes_through_kanmon_at_the_default_clearance():
    req = build_request(origin="Busan", destination="Yokohama", depart="2026-03-03T12:00Z",
                        rta="3d", budget="300ev", seed=101)
    plan = run_request(req)
    assert plan.feasible, plan.infeasible_reasons
    lon, lat, _ = plan.track()
    # through the Kanmon Strait (33.9-34.0 N, 130.8-131.1 E) into the Inland Sea
    assert np.any((lat > 33.85) & (lat < 34.05) & (lon > 130.8) & (lon < 131.1))
    assert np.any((lat > 33.6) & (lat < 34.7) & (lon > 131.5) & (lon < 135.0))
    # shorter than any way round Kyushu: those pass south of Cape Sata (30.98 N 130.67 E), so
    # they are at least Busan -> Cape Sata -> Yokohama in straight lines (784 NM; the sea
    # lane through Kanmon is 658 NM, and keeping 2 NM off the Inland Sea's islands adds some)
    geod = pyproj.Geod(ellps="WGS84")
    _, _, d = geod.inv(lon[:-1], lat[:-1], lon[1:], lat[1:])
    _, _, round_kyushu = geod.inv([lon[0], 130.667], [lat[0], 30.983], [130.667, lon[-1]],
                                  [30.983, lat[-1]])
    assert float(np.sum(d)) < float(np.sum(round_kyushu))
    assert any("clearance 2 NM open sea / 0.5 NM" in w for w in plan.warnings)
