"""Counters of one-off work a process computes rather than reads back from the data directory
(a sea lane's repair, a coastal or strait passage): a plan's clock does not charge it to the
searches still to run, and the plan says how long it took."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass
class OneOffWork:
    """How many pieces of one kind of work this process computed, and their seconds."""

    count: int = 0
    seconds: float = 0.0

    def add(self, seconds: float) -> None:
        """Count one more piece that took `seconds`."""
        self.count += 1
        self.seconds += seconds

    def totals(self) -> tuple[int, float]:
        """(pieces, seconds) so far."""
        return self.count, self.seconds


LANE_REPAIRS = OneOffWork()  # sea lanes repaired at full resolution (`route.seed_repair`)
PASSAGES = OneOffWork()  # coastal and strait passages (`coastal_passages.cached_passage`)
