"""Collect the slices of forecast cycles as they arrive; hand out a cycle only when complete.

Slices and announcements may arrive in any order (late joiners get the transient-local history
of both topics). A cycle is complete when its announcement has been seen and every slice index
``0 .. slice_count-1`` has arrived; a planner never plans on a half-received cycle.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Generic, TypeVar

SliceT = TypeVar("SliceT")


@dataclass
class _PendingCycle(Generic[SliceT]):
    slice_count: int | None = None
    slices: dict[int, SliceT] = field(default_factory=dict)


class CycleAssembler(Generic[SliceT]):
    """Assembles forecast cycles from an announcement and indexed slices."""

    def __init__(self, max_pending_cycles: int = 3) -> None:
        self._pending: dict[str, _PendingCycle[SliceT]] = {}
        self._order: list[str] = []
        self._done: set[str] = set()
        self._max_pending = max_pending_cycles

    def _entry(self, cycle_id: str) -> _PendingCycle[SliceT]:
        if cycle_id not in self._pending:
            self._pending[cycle_id] = _PendingCycle()
            self._order.append(cycle_id)
            while len(self._order) > self._max_pending:
                self._pending.pop(self._order.pop(0), None)
        return self._pending[cycle_id]

    def announce(self, cycle_id: str, slice_count: int) -> list[SliceT] | None:
        """Record a cycle announcement; returns the ordered slices if that completes it."""
        if cycle_id in self._done:
            return None
        self._entry(cycle_id).slice_count = int(slice_count)
        return self._complete(cycle_id)

    def add_slice(
        self, cycle_id: str, index: int, slice_count: int, item: SliceT
    ) -> list[SliceT] | None:
        """Record one slice; returns the ordered slices if that completes its cycle."""
        if cycle_id in self._done:
            return None
        entry = self._entry(cycle_id)
        if not 0 <= index < slice_count:
            raise ValueError(
                f"forecast slice index {index} outside 0..{slice_count - 1} in cycle {cycle_id!r}"
            )
        entry.slices[int(index)] = item
        return self._complete(cycle_id)

    def missing(self, cycle_id: str) -> int | None:
        """Number of slices still missing (None if the cycle was never announced)."""
        entry = self._pending.get(cycle_id)
        if entry is None or entry.slice_count is None:
            return None
        return entry.slice_count - len(entry.slices)

    def _complete(self, cycle_id: str) -> list[SliceT] | None:
        entry = self._pending[cycle_id]
        if entry.slice_count is None or len(entry.slices) < entry.slice_count:
            return None
        if any(i not in entry.slices for i in range(entry.slice_count)):
            return None
        del self._pending[cycle_id]
        self._order.remove(cycle_id)
        self._done.add(cycle_id)
        return [entry.slices[i] for i in range(entry.slice_count)]
