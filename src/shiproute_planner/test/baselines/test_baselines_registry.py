"""Every baseline is reachable through the planner's method registry (`plan --method NAME`)."""

from __future__ import annotations

from datetime import timedelta

import pytest
from shiproute_planner.baselines.registry import GRAPH_METHODS, PYMOO_METHODS
from shiproute_planner.geo.ports import Port
from shiproute_planner.methods import method_names
from shiproute_planner.planning import plan_voyage


def test_all_baselines_registered() -> None:
    names = set(method_names())
    assert set(GRAPH_METHODS) | set(PYMOO_METHODS) <= names
    assert {"seed_ga", "great_circle"} <= names


@pytest.mark.parametrize("method", ["astar", "nsga2_seeded"])
def test_plan_voyage_runs_a_baseline(method: str, land_mask) -> None:
    a = Port("A", "", 35.0, 150.0)
    b = Port("B", "", 36.0, 154.0)
    plan = plan_voyage(a, b, "2026-03-03T18:00Z", timedelta(hours=14), "container_4600teu",
                       None, method=method, budget_s=1.0, land=land_mask, stage_hours=3.0)
    assert plan.method == method
    assert plan.feasible, plan.infeasible_reasons
    assert plan.eta_s <= plan.rta_s
    assert len(plan.waypoints) >= 2
