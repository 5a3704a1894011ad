"""ROS-free replay engine: streams a bag, times it with ``ReplayScheduler``, selects the
ShipState source (or converts NavSatFix), and hands publish events to a callback.

The ROS node supplies the callbacks; tests drive the engine directly. Control calls (pause,
resume, seek, stop) are thread-safe and wake a waiting replay at once.
"""

from __future__ import annotations

import math
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from shiproute_core.topics import SHIP_STATE

from ..bag.bagreader import BagMessage, BagReader
from ..bag.shipstate import NavFixConverter, ShipStateRecord
from ..bag.typestore import NAV_SAT_FIX_TYPE, SHIP_STATE_TYPE, TWIST_TYPES
from .scheduler import ReplayScheduler


@dataclass(frozen=True)
class ReplayConfig:
    """Replay options: rate (<= 0 = as fast as possible), offsets, topic selection."""

    rate: float = 1.0
    start_offset_s: float = 0.0
    loop: bool = False
    pass_topics: tuple[str, ...] = ()  # bag topics to pass through; "*" = all
    remap: dict[str, str] = field(default_factory=dict)  # bag topic -> output topic
    ship_state_topic: str = ""  # bag topic holding ShipState; "" = choose automatically
    max_gap_wall_s: float = 5.0


@dataclass(slots=True)
class ReplayEvent:
    """One thing to publish: a bag ShipState (``data``), a converted one (``record``) or a
    passed-through message (``data``) on output ``topic``."""

    kind: str  # "ship_state", "ship_state_converted" or "pass"
    topic: str
    typename: str
    time_ns: int
    data: memoryview | None = None
    record: ShipStateRecord | None = None


class ReplayEngine:
    """Replays one bag through ``emit(event)`` and ``clock(bag_ns)`` callbacks."""

    def __init__(self, bag: str | Path, config: ReplayConfig) -> None:
        self.config = config
        self.reader = BagReader(bag)
        self.scheduler = ReplayScheduler(config.rate, config.max_gap_wall_s)
        self.start_ns, self.end_ns = self.reader.time_span_ns()
        self.published: dict[str, int] = {}
        self.loops = 0
        self.converted_rejected = 0
        self._cond = threading.Condition()
        self._seek_ns: int | None = None
        self._stop = False
        self._state_topic = config.ship_state_topic or self._pick_ship_state_topic()
        self._converter = NavFixConverter()
        self._fix_topic = ""
        self.finished = False

    def _pick_ship_state_topic(self) -> str:
        states = [t.name for t in self.reader.topics() if t.typename == SHIP_STATE_TYPE]
        if SHIP_STATE in states:
            return SHIP_STATE
        return states[0] if states else ""

    # ------------------------------------------------------------------ control
    def pause(self) -> None:
        """Hold the replay (the bag clock stops)."""
        with self._cond:
            self.scheduler.pause(time.monotonic())
            self._cond.notify_all()

    def resume(self) -> None:
        """Continue after ``pause``."""
        with self._cond:
            self.scheduler.resume(time.monotonic())
            self._cond.notify_all()

    def seek(self, offset_s: float) -> str:
        """Jump to ``offset_s`` from the bag start; returns a problem text or ''."""
        if not math.isfinite(offset_s) or offset_s < 0:
            return f"seek offset {offset_s} s is not a finite non-negative number"
        if self.end_ns > self.start_ns and offset_s * 1e9 > self.end_ns - self.start_ns:
            return f"seek offset {offset_s} s is past the bag end"
        with self._cond:
            self._seek_ns = self.start_ns + int(offset_s * 1e9)
            self._cond.notify_all()
        return ""

    def stop(self) -> None:
        """End ``run`` as soon as possible."""
        with self._cond:
            self._stop = True
            self._cond.notify_all()

    def set_rate(self, rate: float) -> None:
        """Change the replay rate from now on."""
        with self._cond:
            self.scheduler.set_rate(rate, time.monotonic())
            self._cond.notify_all()

    # ------------------------------------------------------------------ running
    def run(self, emit: Callable[[ReplayEvent], None], clock: Callable[[int], None]) -> None:
        """Replay until the end (or forever with loop) or ``stop``; never raises on bad data."""
        start = self.start_ns + int(self.config.start_offset_s * 1e9)
        while not self._stop:
            seek = self._pass(start, emit, clock)
            if self._stop:
                break
            if seek is not None:
                start = seek
                continue
            if not self.config.loop:
                break
            self.loops += 1
            start = self.start_ns + int(self.config.start_offset_s * 1e9)
        self.finished = True

    def _pass(self, start_ns: int, emit: Callable[[ReplayEvent], None],
              clock: Callable[[int], None]) -> int | None:
        """One pass over the bag from ``start_ns``; returns a pending seek target or None."""
        self.scheduler.restart()
        self._converter = NavFixConverter()
        for msg in self.reader.messages(start_ns):
            if not self._wait_due(msg.time_ns):
                return self._take_seek()
            events = self._events(msg)
            if not events:
                continue
            now = time.monotonic()
            clock(self.scheduler.release(msg.time_ns, now))
            for ev in events:
                emit(ev)
                self.published[ev.topic] = self.published.get(ev.topic, 0) + 1
        return self._take_seek()

    def _take_seek(self) -> int | None:
        with self._cond:
            target, self._seek_ns = self._seek_ns, None
            return target

    def _wait_due(self, bag_ns: int) -> bool:
        """Block until ``bag_ns`` is due; False when a seek or stop interrupts."""
        sched = self.scheduler
        if (self._seek_ns is None and not self._stop and not sched.paused
                and sched.wait_s(bag_ns, time.monotonic()) <= 0.0):
            return True  # fast path without the lock: due now (always when unthrottled)
        with self._cond:
            while True:
                if self._stop or self._seek_ns is not None:
                    return False
                if sched.paused:
                    self._cond.wait(0.5)
                    continue
                wait = sched.wait_s(bag_ns, time.monotonic())
                if wait <= 0.0:
                    return True
                self._cond.wait(min(wait, 0.5))

    def _events(self, msg: BagMessage) -> list[ReplayEvent]:
        """Publish events for one bag message (possibly none)."""
        out: list[ReplayEvent] = []
        if msg.typename == SHIP_STATE_TYPE and not self._state_topic:
            self._state_topic = msg.topic  # bag without topic list: first ShipState wins
        if msg.topic == self._state_topic:
            out.append(ReplayEvent("ship_state", SHIP_STATE, SHIP_STATE_TYPE,
                                   msg.time_ns, data=msg.data))
        elif not self._state_topic and msg.typename in (NAV_SAT_FIX_TYPE, *TWIST_TYPES):
            rec = self._convert(msg)
            if rec is not None:
                out.append(ReplayEvent("ship_state_converted", SHIP_STATE,
                                       SHIP_STATE_TYPE, msg.time_ns, record=rec))
        passes = self.config.pass_topics
        if ("*" in passes or msg.topic in passes) and self.reader.is_known(msg):
            topic = self.config.remap.get(msg.topic, msg.topic)
            if topic != SHIP_STATE:
                out.append(ReplayEvent("pass", topic, msg.typename, msg.time_ns, data=msg.data))
        return out

    def _convert(self, msg: BagMessage) -> ShipStateRecord | None:
        if not self.reader.is_known(msg):
            return None
        try:
            obj = self.reader.deserialize(msg)
        except Exception:  # undecodable CDR counts as a rejected fix
            self._converter.rejected += 1
            return None
        if msg.typename in TWIST_TYPES:
            lin = obj.twist.twist.linear if hasattr(obj.twist, "twist") else obj.twist.linear
            self._converter.feed_velocity(msg.time_ns, lin.x, lin.y)
            return None
        if self._fix_topic and msg.topic != self._fix_topic:
            return None
        self._fix_topic = msg.topic
        stamp = obj.header.stamp
        t_ns = stamp.sec * 1_000_000_000 + stamp.nanosec or msg.time_ns
        return self._converter.feed_fix(t_ns, obj.latitude, obj.longitude, obj.status.status)

    def deserialize(self, event: ReplayEvent) -> Any:
        """rosbags object of a ``ship_state`` or ``pass`` event."""
        assert event.data is not None
        return self.reader.store.deserialize_cdr(event.data, event.typename)

    def status(self) -> dict[str, Any]:
        """Progress and counts for diagnostics."""
        clock = self.scheduler.clock_ns
        span = max(1, self.end_ns - self.start_ns)
        counts = self.scheduler.counts
        rep = self.reader.report()
        return {
            "bag_time_ns": clock or 0,
            "progress": 0.0 if clock is None else min(1.0, (clock - self.start_ns) / span),
            "paused": self.scheduler.paused,
            "rate": self.scheduler.rate,
            "loops": self.loops,
            "published": dict(self.published),
            "out_of_order": counts.out_of_order,
            "gaps_jumped": counts.gaps_jumped,
            "gap_skipped_s": counts.gap_skipped_s,
            "max_lag_ms": counts.max_lag_s * 1e3,
            "fixes_rejected": self._converter.rejected,
            "finished": self.finished,
            **{k: v for k, v in rep.items() if k != "problems"},
            "problems": rep["problems"][:5],
        }
