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


class MembersSeen:
    """Slices received per member of the cycles being assembled, so an incomplete ensemble is
    reported with the members it lacks (bounded like the assembler: a few cycles at once)."""

    def __init__(self, capacity: int = 8) -> None:
        self._seen: OrderedDict[str, tuple[int, int, dict[int, int]]] = OrderedDict()
        self._capacity = capacity
        self._lock = threading.Lock()

    def note(self, key: str, item: object) -> None:
        """Count one slice (`item` has member, member_count and count) of cycle `key`."""
        members = max(1, int(getattr(item, "member_count", 1)))
        count = int(getattr(item, "count", 0))
        with self._lock:
            entry = self._seen.setdefault(key, (members, count, {}))
            per = entry[2]
            m = int(getattr(item, "member", 0))
            per[m] = per.get(m, 0) + 1
            while len(self._seen) > self._capacity:
                self._seen.popitem(last=False)

    def missing_text(self, key: str) -> str:
        """'; members [..] lack slices' for an ensemble with members short of slices."""
        with self._lock:
            entry = self._seen.get(key)
        if entry is None or entry[0] <= 1:
            return ""
        members, count, per = entry
        each = count // members if members else 0
        short = [m for m in range(members) if per.get(m, 0) < each]
        return f" of {count}; members {short} of {members} lack slices" if short else ""

    def forget(self, key: str) -> None:
        with self._lock:
            self._seen.pop(key, None)
