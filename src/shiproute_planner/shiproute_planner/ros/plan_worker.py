"""The planner node's planning thread: plan requests in, one run at a time, outcomes out.

Requests coalesce: a request while a run is on is served by the next run, which answers every
request made before it started (a PlanRoute goal waits for the run that answers it). A goal's
own budget is kept until a run takes it, so it never becomes the parameter of later plans.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from ..plan_types import RoutePlan


@dataclass
class PlanInputs:
    """What one planning run works on (a consistent snapshot)."""

    forecast: Any  # ForecastSampler of the cycle
    cycle_id: str
    position: tuple[float, float, float] | None
    previous: RoutePlan | None
    reason: str
    budget_s: float | None = None  # a PlanRoute goal's own budget (None: the parameter)
    request_seq: int = 0  # the latest request this run answers
    objective: str = ""  # a PlanRoute goal's objective ("" = the parameter; "front")
    front_points: int = 9


class PlanWorker:
    """One planning thread. `snapshot(reason, budget_s, seq)` gives the inputs of a run (or why
    none can run yet) under `lock`; `plan_once(inputs)` plans and returns the plan id (None when
    the run was superseded); `failed(inputs, err)` records a failed run and returns its text."""

    def __init__(self, lock: threading.Lock,
                 snapshot: Callable[[str, float | None, int], PlanInputs | str],
                 plan_once: Callable[[PlanInputs], str | None],
                 failed: Callable[[PlanInputs, Exception], str],
                 warm_up: Callable[[], None] | None = None) -> None:
        self._warm_up = warm_up  # run on the thread before the first request is served
        self._wake = threading.Condition(lock)
        self._snapshot = snapshot
        self._plan_once = plan_once
        self._failed = failed
        self._pending: str | None = None
        self._pending_budget_s: float | None = None
        self._pending_objective: tuple[str, int] = ("", 9)  # a goal's objective, front size
        self._request_seq = 0
        self._answered_seq = 0
        self._answer_ok = False
        self._answer_text = ""
        self._done_event = threading.Condition(threading.Lock())
        self._stop = False
        self.cancel = threading.Event()
        self.planning = False
        self._thread = threading.Thread(target=self._work, name="planner", daemon=True)

    def start(self) -> None:
        self._thread.start()

    def busy(self) -> bool:
        """Whether a run is on or a request waits for one."""
        return self.planning or self._pending is not None

    def request(self, reason: str, budget_s: float | None = None, objective: str = "",
                front_points: int = 9) -> int:
        """Ask for a plan (or a time-fuel front); returns the request's number (a goal waits
        for it)."""
        with self._wake:
            self._pending = reason
            self._request_seq += 1
            if budget_s is not None:
                self._pending_budget_s = budget_s  # kept until a run takes it
            if objective:
                self._pending_objective = (objective, front_points)
            self._wake.notify()
            return self._request_seq

    def outcome(self) -> tuple[int, bool, str]:
        """(latest request answered, success, plan id or the reason of failure)."""
        with self._done_event:
            return self._answered_seq, self._answer_ok, self._answer_text

    def wait(self, timeout_s: float) -> None:
        """Wait up to `timeout_s` for a run to end."""
        with self._done_event:
            self._done_event.wait(timeout_s)

    def _answer(self, seq: int, ok: bool, text: str) -> None:
        """Record the outcome of the run that served requests up to `seq`."""
        with self._done_event:
            self._answered_seq, self._answer_ok, self._answer_text = seq, ok, text
            self._done_event.notify_all()

    def _work(self) -> None:
        if self._warm_up is not None:
            self._warm_up()  # a request arriving meanwhile waits: its clock starts after
        while True:
            with self._wake:
                while self._pending is None and not self._stop:
                    self._wake.wait(0.5)
                if self._stop:
                    return
                reason, self._pending = self._pending, None
                assert reason is not None, "the wait above ends only on a request or a stop"
                inputs = self._snapshot(reason, self._pending_budget_s, self._request_seq)
                if isinstance(inputs, str):
                    self._answer(self._request_seq, False, inputs)
                    continue
                self._pending_budget_s = None
                (inputs.objective, inputs.front_points), self._pending_objective = (
                    self._pending_objective, ("", 9))
                self.planning = True
                self.cancel.clear()
            try:
                plan_id = self._plan_once(inputs)
                if plan_id is not None:
                    self._answer(inputs.request_seq, True, plan_id)
            except Exception as err:  # the node never dies on input
                self._answer(inputs.request_seq, False, self._failed(inputs, err))
            finally:
                with self._done_event:
                    self.planning = False
                    self._done_event.notify_all()

    def stop(self, timeout_s: float = 5.0) -> None:
        """End the thread after the run in progress (which is cancelled)."""
        with self._wake:
            self._stop = True
            self.cancel.set()
            self._wake.notify()
        self._thread.join(timeout=timeout_s)
