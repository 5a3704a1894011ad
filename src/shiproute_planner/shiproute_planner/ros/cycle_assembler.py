"""Collect the slices of forecast cycles as they arrive; hand out a cycle only when complete.

Slices and announcements may arrive in any order (late joiners get the transient-local history
of both topics). A cycle is complete when its announcement has been seen and every slice index
``0 .. slice_count-1`` has arrived; a planner never plans on a half-received cycle.

What a cycle is built into is a sink made per cycle from its first slice: by default the
ordered list of slices; the planner node packs each slice into its sampler as it arrives
(`cycle_packer.CyclePacker`), so no copy of the cycle is held besides the sampler.

Thread-safe: slices may be added from several threads at once. A sink's `add` runs outside the
assembler's lock (a planner packs slices in parallel); a slice counts as received only once
its `add` has returned, so `result` never sees a slice still being written.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Generic, Protocol, TypeVar

from ..errors import ForecastCycleError

SliceT = TypeVar("SliceT")
SliceT_contra = TypeVar("SliceT_contra", contravariant=True)


class CycleSink(Protocol[SliceT_contra]):
    """Receives the slices of one cycle; `result` is called once when all have arrived."""

    def add(self, index: int, item: SliceT_contra) -> None: ...

    def result(self) -> Any: ...


class SliceList(Generic[SliceT]):
    """Default sink: the slices themselves, in index order."""

    def __init__(self) -> None:
        self._items: dict[int, SliceT] = {}

    def add(self, index: int, item: SliceT) -> None:
        self._items[index] = item

    def result(self) -> list[SliceT]:
        return [self._items[i] for i in sorted(self._items)]


@dataclass
class _PendingCycle:
    slice_count: int | None = None
    received: set[int] = field(default_factory=set)
    sink: Any = None


class CycleAssembler(Generic[SliceT]):
    """Assembles forecast cycles from an announcement and indexed slices.

    `sink(cycle_id, first_slice)` makes the sink of a new cycle; a sink that rejects a slice
    (raises ValueError) fails its whole cycle, which is then dropped and ignored.
    """

    def __init__(self, max_pending_cycles: int = 3,
                 sink: Callable[[str, SliceT], CycleSink[SliceT]] | None = None,
                 on_evict: Callable[[str, int], None] | None = None) -> None:
        self._pending: dict[str, _PendingCycle] = {}
        self._order: list[str] = []
        self._done: set[str] = set()
        self._max_pending = max_pending_cycles
        self._sink = sink or (lambda _cycle_id, _first: SliceList())
        self._on_evict = on_evict  # (cycle id, slices received) of an incomplete cycle dropped
        self._lock = threading.Lock()

    def _entry(self, cycle_id: str) -> _PendingCycle:
        if cycle_id not in self._pending:
            self._pending[cycle_id] = _PendingCycle()
            self._order.append(cycle_id)
            while len(self._order) > self._max_pending:
                old_id = self._order.pop(0)
                old = self._pending.pop(old_id, None)
                if old is not None and self._on_evict is not None:
                    self._on_evict(old_id, len(old.received))
        return self._pending[cycle_id]

    def announce(self, cycle_id: str, slice_count: int) -> Any | None:
        """Record a cycle announcement; returns the sink's result if that completes it."""
        with self._lock:
            if cycle_id in self._done:
                return None
            self._entry(cycle_id).slice_count = int(slice_count)
            sink = self._complete(cycle_id)
        return None if sink is None else sink.result()

    def add_slice(self, cycle_id: str, index: int, slice_count: int, item: SliceT) -> Any | None:
        """Record one slice; returns the sink's result if that completes its cycle."""
        if not 0 <= index < slice_count:
            raise ForecastCycleError(
                f"forecast slice index {index} outside 0..{slice_count - 1} in cycle {cycle_id!r}"
            )
        with self._lock:
            if cycle_id in self._done:
                return None
            entry = self._entry(cycle_id)
            try:
                if entry.sink is None:
                    entry.sink = self._sink(cycle_id, item)
            except ValueError:
                self._close(cycle_id)
                raise
            sink = entry.sink
        try:
            sink.add(int(index), item)
        except ValueError:
            with self._lock:
                self._close(cycle_id)
            raise
        with self._lock:
            if self._pending.get(cycle_id) is not entry:
                return None  # dropped meanwhile (failed, finished or evicted)
            entry.received.add(int(index))
            sink = self._complete(cycle_id)
        return None if sink is None else sink.result()

    def discard(self, cycle_id: str) -> None:
        """Drop a cycle refused elsewhere (its slices and announcement are ignored from now)."""
        with self._lock:
            self._close(cycle_id)

    def missing(self, cycle_id: str) -> int | None:
        """Number of slices still missing (None if the cycle was never announced)."""
        entry = self._pending.get(cycle_id)
        if entry is None or entry.slice_count is None:
            return None
        return entry.slice_count - len(entry.received)

    def _close(self, cycle_id: str) -> None:
        self._pending.pop(cycle_id, None)
        if cycle_id in self._order:
            self._order.remove(cycle_id)
        self._done.add(cycle_id)

    def _complete(self, cycle_id: str) -> CycleSink[Any] | None:
        """The sink of a cycle that has just become complete (then closed), else None."""
        entry = self._pending[cycle_id]
        if entry.slice_count is None or len(entry.received) < entry.slice_count:
            return None
        if any(i not in entry.received for i in range(entry.slice_count)):
            return None
        older = self._order[: self._order.index(cycle_id)]
        self._close(cycle_id)  # finished: later copies of it are ignored
        for old_id in older:  # announced before it and still incomplete: superseded
            old = self._pending.pop(old_id, None)
            self._order.remove(old_id)
            if old is not None and self._on_evict is not None:
                self._on_evict(old_id, len(old.received))
        return entry.sink
