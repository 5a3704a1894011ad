"""Counts of every input a node refused or dropped, with the last reason, for /diagnostics."""

from __future__ import annotations

import threading


class DropLog:
    """Thread-safe tally per kind of input ('ship_states', 'forecast_slices', ...): how many
    were dropped and why the last one was."""

    def __init__(self, kinds: tuple[str, ...] = ()) -> None:
        self._lock = threading.Lock()
        self._counts: dict[str, int] = dict.fromkeys(kinds, 0)
        self._last: dict[str, str] = dict.fromkeys(kinds, "")

    def drop(self, kind: str, reason: str, n: int = 1) -> int:
        """Record `n` dropped inputs of `kind`; returns the new count."""
        with self._lock:
            self._counts[kind] = self._counts.get(kind, 0) + n
            self._last[kind] = reason
            return self._counts[kind]

    def count(self, kind: str) -> int:
        """How many inputs of `kind` were dropped so far."""
        with self._lock:
            return self._counts.get(kind, 0)

    def last(self, kind: str) -> str:
        """Why the last input of `kind` was dropped ('' when none was)."""
        with self._lock:
            return self._last.get(kind, "")

    def values(self) -> dict[str, str]:
        """Diagnostic key/values: `<kind>_dropped` and `<kind>_last_reason` for every kind."""
        with self._lock:
            out: dict[str, str] = {}
            for kind, n in self._counts.items():
                out[f"{kind}_dropped"] = str(n)
                out[f"{kind}_last_reason"] = self._last[kind] or "none"
            return out
