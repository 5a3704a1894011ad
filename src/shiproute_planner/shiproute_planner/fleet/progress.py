"""Terminal progress of a fleet batch: voyages done / failed / running, skipped as already
planned, elapsed time and the batch's ETA (one line redrawn on a terminal, a line every few
seconds in a log)."""

from __future__ import annotations

import sys
import time
from typing import TextIO

BAR_WIDTH = 28


class FleetProgress:
    """Counts of a batch and their rendering."""

    def __init__(self, total: int, cached: int = 0, stream: TextIO | None = None,
                 log_every_s: float = 5.0) -> None:
        self.total = total
        self.cached = cached
        self.done = 0
        self.failed = 0
        self.running = 0
        self.stream = stream or sys.stderr
        self.tty = bool(getattr(self.stream, "isatty", lambda: False)())
        self.t0 = time.perf_counter()
        self.log_every_s = log_every_s
        self._last_log = -1e9

    def restart_clock(self) -> None:
        """Measure elapsed time and ETA from now (the first voyage submitted), not from the
        cluster's start and worker set-up."""
        self.t0 = time.perf_counter()

    def eta_s(self) -> float | None:
        """Seconds until the batch ends at the rate so far (None before the first result)."""
        finished = self.done + self.failed
        todo = self.total - self.cached - finished
        if finished == 0:
            return None
        return (time.perf_counter() - self.t0) / finished * todo

    def line(self) -> str:
        """The progress line."""
        n = self.total
        filled = self.done + self.failed + self.cached
        k = int(BAR_WIDTH * filled / n) if n else BAR_WIDTH
        eta = self.eta_s()
        eta_txt = "--:--" if eta is None else _mmss(eta)
        return (f"[{'#' * k}{'.' * (BAR_WIDTH - k)}] {filled}/{n}  done {self.done}  "
                f"failed {self.failed}  running {self.running}  already planned "
                f"{self.cached}  elapsed {_mmss(time.perf_counter() - self.t0)}  ETA {eta_txt}")

    def show(self, force: bool = False) -> None:
        """Redraw (terminal) or log a line at most every `log_every_s` (not a terminal)."""
        now = time.perf_counter()
        if self.tty:
            print("\r" + self.line(), end="", file=self.stream, flush=True)
        elif force or now - self._last_log >= self.log_every_s:
            print(self.line(), file=self.stream, flush=True)
            self._last_log = now

    def close(self) -> None:
        """Final state on its own line."""
        if self.tty:
            print("\r" + self.line(), file=self.stream, flush=True)
        else:
            self.show(force=True)


def _mmss(s: float) -> str:
    s = max(round(s), 0)
    if s >= 3600:
        return f"{s // 3600}:{s // 60 % 60:02d}:{s % 60:02d}"
    return f"{s // 60}:{s % 60:02d}"
