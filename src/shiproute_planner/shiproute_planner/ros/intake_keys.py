"""Which publication a forecast slice belongs to, and the publications the planner refused.

Slices are assembled per (cycle id, publication id): a reload of the same file is a new
publication (it is assembled and used again: same content, same result), and a restarted
weather node's slices never complete a cycle its dead predecessor began.
"""

from __future__ import annotations

import threading
from collections import OrderedDict


def assembly_key(cycle_id: str, publication_id: str) -> str:
    """The assembler's key of one publication of a cycle ('' publication: the cycle id)."""
    return f"{cycle_id}\x1f{publication_id}" if publication_id else cycle_id


class RejectedKeys:
    """The most recent refused publications with their reasons (bounded: a flood of bad
    cycles does not grow the planner's memory)."""

    def __init__(self, capacity: int = 256) -> None:
        self._reasons: OrderedDict[str, str] = OrderedDict()
        self._capacity = capacity
        self._lock = threading.Lock()

    def add(self, key: str, reason: str) -> None:
        with self._lock:
            self._reasons[key] = reason
            self._reasons.move_to_end(key)
            while len(self._reasons) > self._capacity:
                self._reasons.popitem(last=False)

    def __contains__(self, key: object) -> bool:
        with self._lock:
            return key in self._reasons

    def reason(self, key: str) -> str:
        with self._lock:
            return self._reasons.get(key, "")
