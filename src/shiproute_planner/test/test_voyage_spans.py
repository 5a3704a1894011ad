"""Spans between straits and canals: one stage length per user's leg, the search budget
shared by genes, no span starved; and a plan's word on its wall-time budget."""

from __future__ import annotations

from types import SimpleNamespace

import pytest
from shiproute_planner.voyage.spans import MIN_SHARE_OF_EVEN, SpanPlan, budget_share, user_legs
from shiproute_planner.voyage.stage_length import OCEAN_STAGE_H

from shiproute_planner import plan_timing

H = 3600.0


def _port(name: str) -> SimpleNamespace:
    return SimpleNamespace(name=name, lon_deg=0.0, lat_deg=0.0)


def test_spans_belong_to_the_users_legs() -> None:
    a, b, c = _port("A"), _port("B"), _port("C")
    g0, g1 = _port("gate"), _port("gate")
    # A -> gate -> gate -> B -> C: three spans on the user's first leg, one on the second
    assert user_legs([a, b, c], [a, g0, g1, b, c]) == (0, 0, 0, 1)
    assert user_legs([a, c], [a, c]) == (0,)


def test_budget_follows_genes_and_starves_no_span() -> None:
    # Busan -> Tsugaru (36 h), the strait (fixed), Tsugaru -> Long Beach (276 h), 12 h stages:
    # 2 stages (5 genes) before the strait, 22 (45 genes) after it
    plan = SpanPlan((0, 0, 0), (12.0, 12.0, 12.0), (True, False, True), (4, 4, 10))
    arrivals = [36 * H, 40 * H, 316 * H]
    assert plan.genes_estimate(0, 36 * H) == 5
    assert plan.genes_estimate(1, 4 * H) == 0  # the strait passage is sailed, not searched
    assert plan.genes_estimate(2, 276 * H) == 45
    assert budget_share(plan, 0, 5, arrivals) == pytest.approx(5 / 50)  # by genes
    assert budget_share(plan, 2, 45, arrivals) == 1.0  # the last span gets all that is left
    # a 1-stage span (3 genes) before a 47-stage one (95 genes): genes would give it 3 %,
    # it keeps a fifth of an even share of two spans (10 %)
    assert budget_share(plan, 0, 3, [36 * H, 40 * H, 616 * H]) == pytest.approx(
        MIN_SHARE_OF_EVEN / 2)
    # two comparable spans split by genes
    even = SpanPlan((0, 0), (12.0, 12.0), (True, True), (12, 12))
    assert budget_share(even, 0, 21, [120 * H, 360 * H]) == pytest.approx(21 / (21 + 39))


def test_a_users_legs_stages_are_shared_among_its_spans(land_mask) -> None:
    """Busan -> Long Beach in 13 days passes the Tsugaru Strait: the 36-hour span before it
    aims at 4 stages (the floor; 12 x 36 / 312 h is 1.4), not 12 of 2.8 h; the ocean span
    after it keeps the reference formulation's 12-hour stages."""
    from shiproute_planner.geo.ports import resolve_port
    from shiproute_planner.straits import route_straits
    from shiproute_planner.voyage.spans import span_plan
    from shiproute_planner.voyage.stage_length import MIN_SPAN_STAGES, leg_stage_hours

    a, b = resolve_port("Busan", land_mask), resolve_port("Long Beach", land_mask)
    ports, _, straits, _, _ = route_straits([a, b], {}, [])
    assert [p.name for p in ports[1:3]] == ["Tsugaru Strait gate"] * 2
    arrivals = [1.5 * 86400, 1.7 * 86400, 13 * 86400]
    plan = span_plan([a, b], ports, set(straits), arrivals, 0.0, None)
    assert plan.user_leg == (0, 0, 0) and plan.optimised == (True, False, True)
    assert plan.target_stages[0] == MIN_SPAN_STAGES
    assert leg_stage_hours(36 * H, 0, plan.target_stages[0]) == pytest.approx(36 / 5)
    assert leg_stage_hours(271 * H, 0, plan.target_stages[2]) == OCEAN_STAGE_H
    # the user's override holds for every span
    assert span_plan([a, b], ports, set(straits), arrivals, 0.0, 2.0).stage_hours == (2.0,) * 3


def test_plan_clock_books_phases_and_says_when_the_budget_was_overrun(monkeypatch) -> None:
    now = [100.0]
    monkeypatch.setattr(plan_timing.time, "perf_counter", lambda: now[0])
    clock = plan_timing.PlanClock()
    now[0] += 1.2
    clock.lap("set-up")
    now[0] += 1.5
    clock.lap("search")
    assert clock.left_s(3.0) == pytest.approx(3.0 - 2.7 - plan_timing.checks_reserve_s(3.0))
    now[0] += 0.2
    clock.lap("checks")
    assert clock.overrun_warning(3.0) == ""  # 2.9 s of 3 s
    now[0] += 0.5  # 3.4 s: over 3 s by more than the tolerated 0.3 s
    clock.lap("checks")
    said = clock.overrun_warning(3.0)
    assert said.startswith("budget: planning took 3.40 s against its budget of 3 s")
    assert "set-up took 1.20 s" in said
    block = clock.block(3.0)
    assert block["total"] == pytest.approx(3.4) and block["search"] == pytest.approx(1.5)
    assert clock.overrun_warning(float("inf")) == ""  # an evaluation budget has no clock
