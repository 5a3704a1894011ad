"""Which forecast cycles put in force got a plan, a failure, or were superseded unplanned.

The planner plans on the newest complete cycle: a plan that runs when a cycle arrives ends on
its own cycle first, and cycles arriving faster than plans are made are coalesced into the newest.
Such a cycle was accepted but never planned on; it is not lost silently: the ledger counts it
and names the last one (and its successor) for /diagnostics, so every accepted cycle is
accounted for: accepted = planned + failed + superseded + (at most one) in force unanswered.
"""

from __future__ import annotations

import threading


class CycleLedger:
    """Thread-safe record of the cycles put in force, one entry per acceptance (a cycle id
    that comes again, e.g. a reloaded file, is a new entry)."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._in_force = ""
        self._in_force_answered = True
        self._just_superseded = ""  # the previous cycle, when `taken` counted it superseded
        self.accepted = 0
        self.planned = 0
        self.failed = 0
        self.superseded = 0
        self.last_superseded = ""

    def taken(self, cycle_id: str) -> None:
        """A cycle was put in force: the one before it, still unanswered, is superseded."""
        with self._lock:
            self._just_superseded = ""
            if not self._in_force_answered:
                self.superseded += 1
                self.last_superseded = f"{self._in_force} (superseded by {cycle_id})"
                self._just_superseded = self._in_force
            self._in_force, self._in_force_answered = cycle_id, False
            self.accepted += 1

    def answered(self, cycle_id: str, planned: bool) -> None:
        """A plan was published (`planned`) or planning failed on `cycle_id`: the cycle in
        force, or the one just superseded when its run ended as the next cycle came in."""
        with self._lock:
            if cycle_id == self._just_superseded and cycle_id != self._in_force:
                self._just_superseded = ""
                self.superseded -= 1  # answered after all
            elif cycle_id != self._in_force or self._in_force_answered:
                return
            else:
                self._in_force_answered = True
            if planned:
                self.planned += 1
            else:
                self.failed += 1

    def values(self) -> dict[str, str]:
        """Diagnostic key/values: cycles accepted, planned, failed and superseded unplanned
        (the last one named), and whether the cycle in force has been answered yet."""
        with self._lock:
            return {"forecast_cycles_accepted": str(self.accepted),
                    "forecast_cycles_planned": str(self.planned),
                    "forecast_cycles_failed": str(self.failed),
                    "forecast_cycles_superseded": str(self.superseded),
                    "forecast_cycles_superseded_last": self.last_superseded or "none",
                    "forecast_cycle_in_force_answered": str(self._in_force_answered)}
