"""Read rosbag2 MCAP bags (directory with metadata.yaml, directory of .mcap, or bare .mcap).

Streams messages file by file through the error-tolerant ``McapScanner`` and deserialises
CDR with a rosbags typestore into which each bag's embedded schemas are registered.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml
from rosbags.typesys.store import Typestore

from ..errors import BagOpenError
from .mcapscan import ChannelInfo, McapScanner
from .typestore import build_typestore, register_schema


@dataclass(slots=True)
class BagMessage:
    """One message as stored: topic, type name, log time [POSIX ns] and CDR bytes."""

    topic: str
    typename: str
    time_ns: int
    data: memoryview


@dataclass(frozen=True)
class TopicInfo:
    """A topic of a bag: name, type and message count (-1 when unknown)."""

    name: str
    typename: str
    count: int


def _load_metadata(path: Path) -> dict[str, Any] | None:
    meta = path / "metadata.yaml"
    if not meta.is_file():
        return None
    try:
        doc = yaml.safe_load(meta.read_text(encoding="utf-8"))
        return doc["rosbag2_bagfile_information"]
    except (yaml.YAMLError, KeyError, TypeError) as exc:
        raise BagOpenError(f"{meta} is not a rosbag2 metadata file: {exc}") from exc


class BagReader:
    """Streaming reader over the MCAP files of one bag; recovery counts in ``report()``."""

    def __init__(self, path: str | Path, store: Typestore | None = None) -> None:
        self.path = Path(path)
        self.store = store if store is not None else build_typestore()
        self.metadata: dict[str, Any] | None = None
        if self.path.is_dir():
            self.metadata = _load_metadata(self.path)
            if self.metadata is not None:
                ident = self.metadata.get("storage_identifier", "mcap")
                if ident != "mcap":
                    raise BagOpenError(f"bag {self.path} uses storage {ident!r}; only MCAP")
                files = [self.path / p for p in self.metadata.get("relative_file_paths", [])]
            else:
                files = sorted(self.path.glob("*.mcap"))
        elif self.path.is_file() and self.path.suffix == ".mcap":
            files = [self.path]
        else:
            raise BagOpenError(f"{self.path} is neither a bag directory nor a .mcap file")
        self.files = [f for f in files if f.is_file()]
        if not self.files:
            raise BagOpenError(f"bag {self.path} has no readable .mcap file")
        self.scanners: list[McapScanner] = []
        self.unknown_types: dict[str, int] = {}
        self._known: dict[str, bool] = {}

    # ------------------------------------------------------------------ overview
    def topics(self) -> list[TopicInfo]:
        """Topics with types and counts from metadata.yaml, else from the MCAP summary."""
        if self.metadata is not None:
            return [
                TopicInfo(
                    t["topic_metadata"]["name"], t["topic_metadata"]["type"], t["message_count"]
                )
                for t in self.metadata.get("topics_with_message_count", [])
            ]
        counts: dict[tuple[str, str], int] = {}
        for f in self.files:
            for key, n in _summary_counts(f).items():
                counts[key] = counts.get(key, 0) + n
        return [TopicInfo(k[0], k[1], n) for k, n in counts.items()]

    def time_span_ns(self) -> tuple[int, int]:
        """(first, last) message time [ns] from metadata/summary, else from a first chunk scan."""
        if self.metadata is not None and self.metadata.get("message_count", 0) > 0:
            start = int(self.metadata["starting_time"]["nanoseconds_since_epoch"])
            return start, start + int(self.metadata["duration"]["nanoseconds"])
        spans = [_summary_span(f) for f in self.files]
        if all(s is not None for s in spans):
            return min(s[0] for s in spans), max(s[1] for s in spans)  # type: ignore[index]
        first = next(iter(McapScanner(self.files[0]).messages()), None)
        t0 = first[1] if first else 0
        return t0, t0

    def expected_count(self) -> int | None:
        """Total message count the bag claims (metadata or summary); None when unknown."""
        if self.metadata is not None:
            return int(self.metadata.get("message_count", 0))
        counts = [_summary_counts(f) for f in self.files]
        if any(not c for c in counts):
            return None
        return sum(sum(c.values()) for c in counts)

    # ------------------------------------------------------------------ messages
    def messages(self, start_ns: int = 0) -> Iterator[BagMessage]:
        """All readable messages in file order with log time >= ``start_ns``."""
        self.scanners = []
        for f in self.files:
            scanner = McapScanner(f)
            self.scanners.append(scanner)
            for cid, t_ns, data in scanner.messages(start_ns):
                chan = scanner.channels.get(cid)
                if chan is None:
                    scanner.load_summary()
                    chan = scanner.channels.get(cid)
                if chan is None:
                    scanner.stats.messages_unknown_channel += 1
                    continue
                yield BagMessage(chan.topic, chan.schema_name, t_ns, data)

    def channels(self) -> list[ChannelInfo]:
        """Channels seen so far by the scanners of the current ``messages`` pass."""
        return [c for s in self.scanners for c in s.channels.values()]

    def is_known(self, msg: BagMessage) -> bool:
        """True when ``msg``'s type can be deserialised (registering its embedded schema)."""
        known = self._known.get(msg.typename)
        if known is None:
            text = next(
                (c.schema_data for c in self.channels() if c.schema_name == msg.typename), ""
            )
            known = register_schema(self.store, msg.typename, text)
            self._known[msg.typename] = known
        if not known:
            self.unknown_types[msg.typename] = self.unknown_types.get(msg.typename, 0) + 1
        return known

    def deserialize(self, msg: BagMessage) -> Any:
        """rosbags message object of ``msg`` (call ``is_known`` first)."""
        return self.store.deserialize_cdr(msg.data, msg.typename)

    def report(self) -> dict[str, Any]:
        """Counts of the last ``messages`` pass: read, skipped, unknown, truncation."""
        st = [s.stats for s in self.scanners]
        read = sum(s.messages_read for s in st)
        expected = self.expected_count()
        skipped_known = sum(s.messages_skipped for s in st)
        return {
            "messages_read": read,
            "messages_expected": expected,
            "messages_skipped": max(skipped_known, expected - read) if expected else skipped_known,
            "chunks_read": sum(s.chunks_read for s in st),
            "chunks_skipped": sum(s.chunks_skipped for s in st),
            "messages_unknown_channel": sum(s.messages_unknown_channel for s in st),
            "unknown_types": dict(self.unknown_types),
            "truncated": any(s.truncated for s in st),
            "resyncs": sum(s.resyncs for s in st),
            "problems": [p for s in st for p in s.problems],
        }


def _summary(path: Path) -> Any:
    from mcap.reader import make_reader

    try:
        with path.open("rb") as f:
            return make_reader(f).get_summary()
    except Exception:  # no or damaged summary: callers fall back to scanning
        return None


def _summary_counts(path: Path) -> dict[tuple[str, str], int]:
    summ = _summary(path)
    if summ is None or summ.statistics is None:
        return {}
    out: dict[tuple[str, str], int] = {}
    for cid, chan in summ.channels.items():
        schema = summ.schemas.get(chan.schema_id)
        key = (chan.topic, schema.name if schema else "")
        out[key] = out.get(key, 0) + summ.statistics.channel_message_counts.get(cid, 0)
    return out


def _summary_span(path: Path) -> tuple[int, int] | None:
    summ = _summary(path)
    if summ is None or summ.statistics is None:
        return None
    return summ.statistics.message_start_time, summ.statistics.message_end_time
