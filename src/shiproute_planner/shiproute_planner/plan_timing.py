"""Where a plan's wall time went, and the plan's word on its budget.

`plan_voyage` runs set-up (ship model, depth grid, canals, straits, schedule), then per span
the passages (coastal approaches, strait passages, canals), the constant-RPM baseline and the
search, then the checks of the finished plan (route check at full resolution, forecast
statement). The search of each span gets what the others left of `budget_s`
(`voyage.spans.budget_share`); a plan that still overran says by how much and which phase
took the time, so a budget that cannot be kept is never kept silently. Seconds spent building
full-resolution coastline tiles (once per machine and region) and repairing a baseline's sea
lane at full resolution (once per lane: a re-plan from a new position meets a new one) and
computing a coastal or strait passage first met on the machine are not counted against the
spans still to run (tiles up to the budget, `tile_allowance`), so a
span that built tiles does not take the time of the next and a re-plan's search keeps its
time.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

from .geo.fine_distance import tile_builds
from .one_off_work import PASSAGES

PHASES = ("set-up", "passages", "baselines", "search", "checks")
# a plan may end this much after its budget before it says so: the search stops at its
# deadline only between generations (one generation of the storm voyage takes ~0.03-0.1 s
# on an idle core) and the final checks are estimated, not known, beforehand
OVERRUN_TOLERANCE_S = 0.25
OVERRUN_TOLERANCE_SHARE = 0.10
# the checks of the finished plan (route check on the polygons, forecast statement) take
# ~0.05-0.2 s on an ocean voyage; the search stops early enough to leave them this
CHECKS_RESERVE_S = 0.15
CHECKS_RESERVE_SHARE = 0.05


MAX_CHECKS_SHARE = 0.4  # a measured checks time reserves at most this share of the budget


def checks_reserve_s(budget_s: float, measured_s: float = 0.0) -> float:
    """Wall time kept from the search for the checks of the finished plan: the estimate,
    or what the checks of the previous plan of the voyage took (`measured_s`, a re-plan's
    budget of 0.5 s cannot leave them 25 ms), within MAX_CHECKS_SHARE of the budget."""
    estimate = min(CHECKS_RESERVE_S, CHECKS_RESERVE_SHARE * budget_s)
    return max(estimate, min(measured_s, MAX_CHECKS_SHARE * budget_s))


def previous_checks_s(previous: object) -> float:
    """What the checks of a previous plan (its extra["timing_s"]) took [s]; 0 when unknown."""
    timing = getattr(previous, "extra", {}).get("timing_s", {}) if previous is not None else {}
    value = timing.get("checks", 0.0) if isinstance(timing, dict) else 0.0
    return float(value) if isinstance(value, int | float) and value > 0 else 0.0


def tolerated_overrun_s(budget_s: float) -> float:
    """How far past `budget_s` a plan may end without a warning."""
    return max(OVERRUN_TOLERANCE_S, OVERRUN_TOLERANCE_SHARE * budget_s)


@dataclass
class PlanClock:
    """Wall time per phase of one plan [s]: `lap(phase)` books the time since the last lap
    (or the start) to `phase`, so sequential code is timed without being re-indented."""

    t0: float = field(default_factory=lambda: time.perf_counter())
    checks_measured_s: float = 0.0  # the checks of the voyage's previous plan took this
    spent_s: dict[str, float] = field(default_factory=lambda: dict.fromkeys(PHASES, 0.0))
    mark: float = field(default=0.0)
    tiles_s0: float = field(default_factory=lambda: tile_builds()[1])  # tile builds at start
    excused_s: float = 0.0  # one-off work before a search (a baseline's lane repair) [s]
    passages0: tuple[int, float] = field(default_factory=PASSAGES.totals)  # computed at start

    def __post_init__(self) -> None:
        self.mark = self.t0

    def tile_build_s(self) -> float:
        """Seconds spent building coastline tiles since the plan started."""
        return max(tile_builds()[1] - self.tiles_s0, 0.0)

    def passages_built(self) -> tuple[int, float]:
        """(passages, seconds) computed afresh since the plan started (coastal approaches and
        straits first met on this machine; later plans read them back)."""
        n, seconds = PASSAGES.totals()
        return n - self.passages0[0], max(seconds - self.passages0[1], 0.0)

    def passage_statement(self) -> tuple[str, ...]:
        """The plan's word on passages it computed afresh (none when all were read back)."""
        n, seconds = self.passages_built()
        if n == 0:
            return ()
        return (f"passages: {n} coastal or strait passage(s) computed afresh in {seconds:.2f} s "
                "(first met on this machine, kept for later plans); the search's clock was "
                "extended by as much",)

    def excuse(self, seconds: float) -> None:
        """Not charge `seconds` of one-off work before a search (a baseline's sea lane
        repaired afresh, once per span) to the searches still to run."""
        self.excused_s += max(seconds, 0.0)

    def elapsed_s(self) -> float:
        """Seconds since the plan started."""
        return time.perf_counter() - self.t0

    def lap(self, phase: str) -> float:
        """Book the time since the last lap to `phase`; returns the seconds booked."""
        now = time.perf_counter()
        spent, self.mark = now - self.mark, now
        self.spent_s[phase] = self.spent_s.get(phase, 0.0) + spent
        return spent

    def left_s(self, budget_s: float) -> float:
        """Budget left for the searches still to run, keeping the checks' reserve (tile
        builds so far excused up to the budget: a search may meet tiles without end; work
        `excuse`d before a search and passages computed afresh, in full: one per approach
        or strait)."""
        excused = (min(self.tile_build_s(), budget_s) + self.excused_s
                   + self.passages_built()[1])
        return (budget_s - self.elapsed_s() + excused
                - checks_reserve_s(budget_s, self.checks_measured_s))

    def block(self, budget_s: float) -> dict[str, float]:
        """The plan's `extra["timing_s"]`: budget, total and each phase [s]."""
        out = {"budget": float(budget_s), "total": round(self.elapsed_s(), 3)}
        out.update({k: round(v, 3) for k, v in self.spent_s.items()})
        return out

    def overrun_warning(self, budget_s: float) -> str:
        """A warning when the plan ended later than its budget allows, naming the phase
        outside the search that took most time ('' when within it or unbounded)."""
        total = self.elapsed_s()
        if not budget_s < float("inf") or total <= budget_s + tolerated_overrun_s(budget_s):
            return ""
        others = {k: v for k, v in self.spent_s.items() if k != "search"}
        worst = max(others, key=lambda k: others[k]) if others else "set-up"
        return (f"budget: planning took {total:.2f} s against its budget of {budget_s:g} s; "
                f"the search had {self.spent_s.get('search', 0.0):.2f} s, {worst} took "
                f"{others.get(worst, 0.0):.2f} s (" + ", ".join(
                    f"{k} {v:.2f} s" for k, v in others.items()) + ")")
