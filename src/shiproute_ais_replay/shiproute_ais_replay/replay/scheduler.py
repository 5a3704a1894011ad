"""ROS-free replay timing: maps bag time to wall time at a rate, with pause, seek and gap jumps.

Wall times are monotonic seconds passed in by the caller (so tests drive it with fake time).
A message due in the past is released at once and its lateness recorded as lag; a message
older than the newest one released (out of order) is released at once without moving the
clock back; a gap longer than ``max_gap_wall_s`` of wall time re-anchors the schedule so the
replay jumps ahead instead of sleeping for days.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass
class ScheduleCounts:
    """Timing anomalies seen so far."""

    out_of_order: int = 0
    gaps_jumped: int = 0
    gap_skipped_s: float = 0.0
    max_lag_s: float = 0.0


class ReplayScheduler:
    """Decides how long to wait before releasing each bag message."""

    def __init__(self, rate: float = 1.0, max_gap_wall_s: float = 5.0) -> None:
        self.rate = rate
        self.max_gap_wall_s = max_gap_wall_s
        self.counts = ScheduleCounts()
        self._anchor: tuple[float, int] | None = None  # (wall s, bag ns)
        self._last_ns: int | None = None
        self._paused_at: float | None = None

    @property
    def unthrottled(self) -> bool:
        """True when rate <= 0: release everything as fast as possible."""
        return self.rate <= 0.0

    @property
    def paused(self) -> bool:
        """True while paused."""
        return self._paused_at is not None

    @property
    def clock_ns(self) -> int | None:
        """Newest bag time released (monotonic bag clock), None before the first message."""
        return self._last_ns

    def wait_s(self, bag_ns: int, now_s: float) -> float:
        """Seconds to wait (>= 0) before ``bag_ns`` is due; re-anchors over long gaps."""
        if self._anchor is None:
            self._anchor = (now_s, bag_ns)
            return 0.0
        if self.unthrottled or (self._last_ns is not None and bag_ns <= self._last_ns):
            return 0.0
        if self._last_ns is not None:
            gap_wall = (bag_ns - self._last_ns) * 1e-9 / self.rate
            if gap_wall > self.max_gap_wall_s:
                self.counts.gaps_jumped += 1
                self.counts.gap_skipped_s += (bag_ns - self._last_ns) * 1e-9
                self._anchor = (max(now_s, self._due(self._last_ns)), bag_ns)
        return max(0.0, self._due(bag_ns) - now_s)

    def release(self, bag_ns: int, now_s: float) -> int:
        """Record that ``bag_ns`` was published at ``now_s``; returns the bag clock [ns]."""
        if self._last_ns is not None and bag_ns < self._last_ns:
            self.counts.out_of_order += 1
            return self._last_ns
        if self._anchor is not None and not self.unthrottled:
            self.counts.max_lag_s = max(self.counts.max_lag_s, now_s - self._due(bag_ns))
        self._last_ns = bag_ns
        return bag_ns

    def _due(self, bag_ns: int) -> float:
        assert self._anchor is not None
        wall0, bag0 = self._anchor
        return wall0 + (bag_ns - bag0) * 1e-9 / self.rate

    def pause(self, now_s: float) -> None:
        """Stop the schedule; waiting callers should poll ``paused``."""
        if self._paused_at is None:
            self._paused_at = now_s

    def resume(self, now_s: float) -> None:
        """Continue where paused: the schedule shifts by the paused duration."""
        if self._paused_at is None:
            return
        if self._anchor is not None:
            self._anchor = (self._anchor[0] + now_s - self._paused_at, self._anchor[1])
        self._paused_at = None

    def set_rate(self, rate: float, now_s: float) -> None:
        """Change the rate from now on, keeping the current bag position."""
        if self._last_ns is not None:
            self._anchor = (now_s, self._last_ns)
        self.rate = rate

    def restart(self) -> None:
        """Forget the anchor and clock (after a seek or a loop): the next message is due now."""
        self._anchor = None
        self._last_ns = None
