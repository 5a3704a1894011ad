"""The live feed: one server-sent-events stream per page, each behind its own bounded queue.

`Feed.publish` encodes an event once and offers the same bytes to every client without ever
waiting: a client whose queue is full (a slow or stalled browser) has its backlog discarded and
is marked for a resync, so its writer sends one fresh snapshot instead of the stale updates.
The node's callbacks are never held up by a page, and a page costs at most `depth` events.
"""

from __future__ import annotations

import itertools
import json
import math
import threading
from collections import deque
from typing import Any

from .errors import DisplayError


class FeedFullError(DisplayError):
    """The display serves its maximum number of live pages already."""


RESYNC = b""  #: returned by Client.next when the client must be sent a fresh snapshot


def json_safe(v: Any) -> Any:
    """`v` with every non-finite float replaced by None (standard JSON has no NaN)."""
    if isinstance(v, float):
        return v if math.isfinite(v) else None
    if isinstance(v, dict):
        return {k: json_safe(x) for k, x in v.items()}
    if isinstance(v, list | tuple):
        return [json_safe(x) for x in v]
    return v


def dumps(payload: Any) -> bytes:
    """Compact standard JSON (NaN/inf -> null)."""
    return json.dumps(json_safe(payload), separators=(",", ":"), allow_nan=False,
                      default=str).encode()


def encode_event(name: str, payload: dict[str, Any], seq: int) -> bytes:
    """One SSE frame: id, event name, one data line of compact JSON (NaN -> null)."""
    data = dumps(payload).decode()
    return f"id: {seq}\nevent: {name}\ndata: {data}\n\n".encode()


class Client:
    """The queue of one connected page."""

    def __init__(self, client_id: int, depth: int) -> None:
        self.client_id = client_id
        self.depth = depth
        self._queue: deque[bytes] = deque()
        self._cond = threading.Condition()
        self.dropped = 0
        self.sent = 0
        self._resync = False
        self.closed = False

    def offer(self, frame: bytes) -> None:
        """Queue a frame; when full, drop the backlog and ask for a resync (never blocks)."""
        with self._cond:
            if self.closed:
                return
            if len(self._queue) >= self.depth:
                self.dropped += len(self._queue) + 1
                self._queue.clear()
                self._resync = True
            else:
                self._queue.append(frame)
            self._cond.notify()

    def next(self, timeout_s: float) -> bytes | None:
        """The next frame, RESYNC when a snapshot is due, None after `timeout_s` of quiet."""
        with self._cond:
            if not self._queue and not self._resync and not self.closed:
                self._cond.wait(timeout_s)
            if self._resync:
                self._resync = False
                return RESYNC
            return self._queue.popleft() if self._queue else None

    def queued(self) -> int:
        """Frames waiting."""
        with self._cond:
            return len(self._queue)

    def close(self) -> None:
        """Stop accepting frames and wake the writer."""
        with self._cond:
            self.closed = True
            self._queue.clear()
            self._cond.notify()


class Feed:
    """Registry of connected pages and the fan-out of events to them."""

    def __init__(self, max_clients: int = 16, depth: int = 64) -> None:
        self.max_clients = max_clients
        self.depth = depth
        self._clients: dict[int, Client] = {}
        self._lock = threading.Lock()
        self._ids = itertools.count(1)
        self._seq = itertools.count(1)
        self.served = 0
        self.dropped_gone = 0  # frames dropped for clients that have since disconnected
        self._last_seq = 0

    def subscribe(self) -> Client:
        """A new client queue; FeedFullError when `max_clients` pages are connected."""
        with self._lock:
            if len(self._clients) >= self.max_clients:
                raise FeedFullError(f"display already serves {self.max_clients} live pages")
            c = Client(next(self._ids), self.depth)
            self._clients[c.client_id] = c
            self.served += 1
            return c

    def unsubscribe(self, client: Client) -> None:
        """Forget a client (its writer has ended)."""
        client.close()
        with self._lock:
            if self._clients.pop(client.client_id, None) is not None:
                self.dropped_gone += client.dropped

    def publish(self, name: str, payload: dict[str, Any]) -> bytes:
        """Encode once and offer to every client; returns the frame."""
        with self._lock:
            self._last_seq = next(self._seq)
            seq = self._last_seq
        frame = encode_event(name, payload, seq)
        with self._lock:
            clients = list(self._clients.values())
        for c in clients:
            c.offer(frame)
        return frame

    def frame(self, name: str, payload: dict[str, Any]) -> bytes:
        """An event frame for one client only (the snapshot on connect or resync); it carries
        the last published sequence number, so pages count gaps in the shared stream only."""
        with self._lock:
            seq = self._last_seq
        return encode_event(name, payload, seq)

    def stats(self) -> dict[str, int]:
        """Connected clients, clients served so far, frames dropped for slow clients."""
        with self._lock:
            clients = list(self._clients.values())
        queued = [c.queued() for c in clients]
        return {"clients": len(clients), "served": self.served,
                "dropped": self.dropped_gone + sum(c.dropped for c in clients),
                "queued": sum(queued), "queued_max": max(queued, default=0),
                "depth": self.depth}
