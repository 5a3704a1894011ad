"""The seeding phase's share of a span's search: seeds are built (converted, repaired,
evaluated) only until it is spent, so a stale re-plan whose first-use costs (coastal cells
resolved, a kernel compiled, a storm that breaks every given seed) pile up still leaves the
GA most of its budget and reaches its generations."""

from __future__ import annotations

import time
from dataclasses import dataclass

# share of the span's wall time the seeds may take before the GA starts: a cold plan's ~25
# seed tracks take ~0.1-0.3 s of a 3-s span on an idle core, a stale re-plan's repairs about
# as much again, so this share is rarely binding and binds hard where a first use stalls
SEEDING_SHARE = 0.3
# a short search (a 0.5-s re-plan's span: ~0.3 s) lives on its repairs more than on its few
# generations: its seeding gets at least this long, within SEEDING_MAX_SHARE of the search
SEEDING_MIN_S = 0.25
SEEDING_MAX_SHARE = 0.6
# a seeding phase that took this many times its share has stalled (a first use on a loaded
# machine): even the work that otherwise always runs (the first round of repairs) is skipped
OVERRUN_FACTOR = 2.0


@dataclass(frozen=True)
class SeedingBudget:
    """Wall-clock deadline (time.perf_counter) of one span's seeding phase."""

    start_s: float
    deadline_s: float

    def spent(self) -> bool:
        """Whether the seeding phase has used its share: build no more seeds."""
        return time.perf_counter() >= self.deadline_s

    def overrun(self) -> bool:
        """Whether the seeding phase has taken OVERRUN_FACTOR times its share: it stalled,
        and the GA needs what is left of the search."""
        return self.elapsed_s() >= OVERRUN_FACTOR * self.share_s()

    def elapsed_s(self) -> float:
        """Seconds the seeding phase has taken so far."""
        return time.perf_counter() - self.start_s

    def share_s(self) -> float:
        """The seconds the seeding phase was given."""
        return self.deadline_s - self.start_s


def seeding_budget(t_start_s: float, search_s: float) -> SeedingBudget:
    """The seeding budget of a span whose search started at `t_start_s` (perf_counter) and
    may run `search_s` seconds (infinite: never spent): SEEDING_SHARE of it, at least
    SEEDING_MIN_S within SEEDING_MAX_SHARE."""
    search_s = max(search_s, 0.0)
    share_s = min(max(SEEDING_SHARE * search_s, SEEDING_MIN_S), SEEDING_MAX_SHARE * search_s)
    return SeedingBudget(t_start_s, t_start_s + share_s)


def unbounded() -> SeedingBudget:
    """A budget that is never spent (callers outside a timed search)."""
    now = time.perf_counter()
    return SeedingBudget(now, float("inf"))
