"""The planner node warms up before its first plan: the warm-up runs on the planning thread
before any request is served (a request arriving meanwhile waits, its clock not started), and
the warm-up plans the configured voyage in calm water without a search."""

from __future__ import annotations

import threading
import time

from shiproute_planner.plan_timing import checks_reserve_s, previous_checks_s
from shiproute_planner.ros.parameters import PARAMETERS
from shiproute_planner.ros.plan_worker import PlanInputs, PlanWorker
from shiproute_planner.ros.startup import warm_planner, warm_up_logged


def test_warm_up_runs_before_the_first_plan() -> None:
    events: list[tuple[str, float]] = []
    lock = threading.Lock()

    def warm() -> None:
        events.append(("warm-up start", time.perf_counter()))
        time.sleep(0.3)
        events.append(("warm-up end", time.perf_counter()))

    def snapshot(reason: str, budget_s: float | None, seq: int) -> PlanInputs:
        return PlanInputs(None, "cycle", None, None, reason, budget_s, seq)

    def plan_once(inputs: PlanInputs) -> str:
        events.append(("plan", time.perf_counter()))
        return "plan-1"

    worker = PlanWorker(lock, snapshot, plan_once, lambda i, e: str(e), warm)
    worker.start()
    seq = worker.request("first cycle")  # arrives while the warm-up runs
    deadline = time.perf_counter() + 10.0
    while worker.outcome()[0] < seq and time.perf_counter() < deadline:
        worker.wait(0.1)
    worker.stop()
    assert [e[0] for e in events] == ["warm-up start", "warm-up end", "plan"]
    assert worker.outcome() == (seq, True, "plan-1")


def test_warm_up_of_an_impossible_voyage_is_a_warning_not_a_dead_thread() -> None:
    said: list[str] = []

    class Log:
        def info(self, text: str) -> None:
            said.append("info: " + text)

        def warning(self, text: str) -> None:
            said.append("warning: " + text)

    params = {k: v for k, (v, _) in PARAMETERS.items()} | {"destination": "Atlantis"}
    warm_up_logged(params.__getitem__, Log())
    assert len(said) == 1 and said[0].startswith("warning: warm-up skipped")
    assert "Atlantis" in said[0]


def test_warm_planner_sets_up_the_configured_voyage() -> None:
    params = {k: v for k, (v, _) in PARAMETERS.items()} | {
        "origin": "35,160", "destination": "38,190", "departure_time": "2026-03-10T00:00:00Z",
        "rta": "2026-03-15T00:00:00Z", "default_bathymetry": False}
    text = warm_planner(params.__getitem__)
    assert text.startswith("warm-up: ") and "calm water" in text


def test_a_replan_keeps_what_the_last_checks_took_for_them() -> None:
    class Plan:
        def __init__(self) -> None:
            self.extra = {"timing_s": {"checks": 0.12}}

    assert previous_checks_s(Plan()) == 0.12
    assert previous_checks_s(None) == 0.0
    # 0.5 s budget: 25 ms by the estimate, the 0.12 s the last checks took when measured,
    # never more than 40 % of the budget
    assert checks_reserve_s(0.5) == 0.025
    assert checks_reserve_s(0.5, 0.12) == 0.12
    assert checks_reserve_s(0.5, 0.9) == 0.2
    assert checks_reserve_s(3.0, 0.05) == 0.15  # the estimate when it is larger
