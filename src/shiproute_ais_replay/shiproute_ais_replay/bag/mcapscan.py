"""Streaming, error-tolerant MCAP scanner: yields messages chunk by chunk, skips what is broken.

rosbags' and mcap's readers stop at the first bad chunk; this scanner reads records in file
order, verifies each chunk (decompression, CRC, record framing), skips a bad chunk (counting
its messages from the message-index records that follow it), resynchronises after a damaged
record header and stops cleanly at a truncated end. Only one chunk is held in memory.
"""

from __future__ import annotations

import struct
import zlib
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import BinaryIO

from ..errors import BagFormatError

MAGIC = b"\x89MCAP0\r\n"
OP_SCHEMA, OP_CHANNEL, OP_MESSAGE, OP_CHUNK, OP_MESSAGE_INDEX = 0x03, 0x04, 0x05, 0x06, 0x07
OP_FOOTER, OP_DATA_END = 0x02, 0x0F
KNOWN_OPS = frozenset(range(0x01, 0x10))
_U16, _U32, _U64 = struct.Struct("<H"), struct.Struct("<I"), struct.Struct("<Q")
_REC = struct.Struct("<BQ")
_MSG = struct.Struct("<HIQQ")
_CHUNK_HEAD = struct.Struct("<QQQI")
RESYNC_BLOCK = 1 << 20


@dataclass(frozen=True)
class ChannelInfo:
    """An MCAP channel with its schema (``schema_data`` is the message definition text)."""

    channel_id: int
    topic: str
    message_encoding: str
    schema_name: str
    schema_encoding: str
    schema_data: str
    metadata: dict[str, str]


@dataclass
class ScanStats:
    """What the scanner read and what it had to skip."""

    chunks_read: int = 0
    chunks_skipped: int = 0
    messages_read: int = 0
    messages_skipped: int = 0
    messages_unknown_channel: int = 0
    resyncs: int = 0
    truncated: bool = False
    problems: list[str] = field(default_factory=list)

    def note(self, text: str) -> None:
        """Keep the first few problem descriptions (enough to report, bounded in memory)."""
        if len(self.problems) < 20:
            self.problems.append(text)


def _string(buf: memoryview, pos: int) -> tuple[str, int]:
    n = _U32.unpack_from(buf, pos)[0]
    end = pos + 4 + n
    if end > len(buf):
        raise ValueError("string runs past its record")
    return bytes(buf[pos + 4 : end]).decode("utf-8"), end


def _decompress(kind: str, data: bytes, size: int) -> bytes:
    if kind == "":
        return data
    if kind == "zstd":
        try:
            from compression import zstd
        except ImportError:
            from backports import zstd
        return zstd.decompress(data)
    if kind == "lz4":
        import lz4.frame

        return lz4.frame.decompress(data)
    raise ValueError(f"unsupported chunk compression {kind!r}")


class McapScanner:
    """Iterate the messages of one .mcap file with error recovery; see ``stats`` afterwards."""

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path)
        self.size = self.path.stat().st_size
        self.stats = ScanStats()
        self.channels: dict[int, ChannelInfo] = {}
        self._schemas: dict[int, tuple[str, str, str]] = {}
        self._pending: dict[int, dict] = {}
        self._summary_loaded = False
        self._bad_chunk = False  # the last chunk was unusable or cut short
        self._partial = 0  # messages given from a chunk cut short

    # ------------------------------------------------------------------ records
    def _schema(self, buf: memoryview) -> None:
        sid = _U16.unpack_from(buf, 0)[0]
        name, pos = _string(buf, 2)
        enc, pos = _string(buf, pos)
        n = _U32.unpack_from(buf, pos)[0]
        self._schemas[sid] = (name, enc, bytes(buf[pos + 4 : pos + 4 + n]).decode("utf-8"))

    def _channel(self, buf: memoryview) -> None:
        cid, sid = struct.unpack_from("<HH", buf, 0)
        topic, pos = _string(buf, 4)
        menc, pos = _string(buf, pos)
        mlen = _U32.unpack_from(buf, pos)[0]
        pos += 4
        end = pos + mlen
        meta: dict[str, str] = {}
        while pos < end:
            key, pos = _string(buf, pos)
            meta[key], pos = _string(buf, pos)
        name, enc, text = self._schemas.get(sid, ("", "", ""))
        self.channels[cid] = ChannelInfo(cid, topic, menc, name, enc, text, meta)

    def _records(self, buf: memoryview) -> Iterator[tuple[int, int, memoryview]]:
        """(channel id, log time ns, data) of the Message records in ``buf``."""
        pos, n = 0, len(buf)
        while pos < n:
            if pos + 9 > n:
                raise ValueError("record header runs past the chunk end")
            op, length = _REC.unpack_from(buf, pos)
            body = buf[pos + 9 : pos + 9 + length]
            if len(body) != length:
                raise ValueError(f"record of {length} bytes runs past the chunk end")
            pos += 9 + length
            if op == OP_MESSAGE:
                cid, _, log_ns, _ = _MSG.unpack_from(body, 0)
                yield cid, log_ns, body[22:]
            elif op == OP_SCHEMA:
                self._schema(body)
            elif op == OP_CHANNEL:
                self._channel(body)
            elif op not in KNOWN_OPS:
                raise ValueError(f"unknown record opcode 0x{op:02x} inside chunk")

    # ------------------------------------------------------------------ summary
    def load_summary(self) -> None:
        """Read schemas and channels from the summary section (when the file has one)."""
        if self._summary_loaded:
            return
        self._summary_loaded = True
        try:
            with self.path.open("rb") as f:
                f.seek(self.size - 8 - 29)
                tail = f.read(29 + 8)
                if tail[-8:] != MAGIC or tail[0] != OP_FOOTER:
                    return
                start = _U64.unpack_from(tail, 9)[0]
                if start == 0:
                    return
                f.seek(start)
                data = memoryview(f.read(self.size - 37 - start))
            for op, body in self._summary_records(data):
                if op == OP_SCHEMA:
                    self._schema(body)
                elif op == OP_CHANNEL:
                    self._channel(body)
        except (OSError, ValueError, struct.error, UnicodeDecodeError) as exc:
            self.stats.note(f"summary unreadable: {exc}")

    @staticmethod
    def _summary_records(data: memoryview) -> Iterator[tuple[int, memoryview]]:
        pos = 0
        while pos + 9 <= len(data):
            op, length = _REC.unpack_from(data, pos)
            yield op, data[pos + 9 : pos + 9 + length]
            pos += 9 + length

    # ------------------------------------------------------------------ main loop
    def messages(self, start_ns: int = 0) -> Iterator[tuple[int, int, memoryview]]:
        """Yield (channel id, log time ns, CDR bytes) in file order from ``start_ns`` on.

        Chunks that end before ``start_ns`` are skipped without decompressing them.
        """
        with self.path.open("rb") as f:
            if f.read(8) != MAGIC:
                raise BagFormatError(f"{self.path} is not an MCAP file (bad magic)")
            yield from self._scan(f, start_ns)

    def _scan(self, f: BinaryIO, start_ns: int) -> Iterator[tuple[int, int, memoryview]]:
        """Messages of the records from the file position on, skipping damaged ones."""
        self._bad_chunk, self._partial = False, 0
        while True:
            pos = f.tell()
            head = f.read(9)
            if len(head) < 9:
                if head:
                    self._truncated(pos, "record header")
                return
            op, length = _REC.unpack_from(head, 0)
            if op not in KNOWN_OPS or pos + 9 + length > self.size:
                if not self._skip_damaged(f, pos, op, length):
                    return
                continue
            if op in (OP_DATA_END, OP_FOOTER):
                return
            if op == OP_CHUNK:
                yield from self._chunk_messages(f, length, start_ns)
            else:
                yield from self._top_record(op, memoryview(f.read(length)), start_ns)

    def _skip_damaged(self, f: BinaryIO, pos: int, op: int, length: int) -> bool:
        """Note a damaged record at ``pos`` and resync; False when nothing is left."""
        if op == OP_CHUNK:
            self.stats.chunks_skipped += 1
        self._truncated(pos, f"record 0x{op:02x} of {length} bytes")
        return self._resync(f, pos + 1)

    def _chunk_messages(self, f: BinaryIO, length: int,
                        start_ns: int) -> Iterator[tuple[int, int, memoryview]]:
        """Messages of one chunk record, streamed; framing is checked as we go (a chunk cut
        short counts the messages it gave, its message index then counts the rest lost)."""
        raw = self._chunk(f, length, start_ns)
        self._bad_chunk = False
        if raw is None:
            self._bad_chunk, self._partial = True, 0
            return
        if not raw:
            return
        self._partial = 0
        try:
            for msg in self._records(memoryview(raw)):
                if msg[1] >= start_ns:
                    self.stats.messages_read += 1
                    self._partial += 1
                    yield msg
            self.stats.chunks_read += 1
        except (ValueError, struct.error, UnicodeDecodeError) as exc:
            self.stats.chunks_skipped += 1
            self.stats.note(f"chunk ending at byte {f.tell()} cut short: {exc}")
            self._bad_chunk = True

    def _top_record(self, op: int, body: memoryview,
                    start_ns: int) -> Iterator[tuple[int, int, memoryview]]:
        """A record outside chunks: a message, a schema, a channel, or the message index
        that tells how many messages a damaged chunk lost."""
        if op == OP_MESSAGE_INDEX and self._bad_chunk:
            lost = _U32.unpack_from(body, 2)[0] // 16
            self.stats.messages_skipped += max(0, lost - self._partial)
            self._partial = max(0, self._partial - lost)
        elif op == OP_MESSAGE:
            cid, _, log_ns, _ = _MSG.unpack_from(body, 0)
            if log_ns >= start_ns:
                self.stats.messages_read += 1
                yield cid, log_ns, body[22:]
        elif op == OP_SCHEMA:
            self._schema(body)
        elif op == OP_CHANNEL:
            self._channel(body)

    def _chunk(self, f: BinaryIO, length: int, start_ns: int) -> bytes | None:
        """Decompressed, CRC-checked records of one chunk; b"" when the chunk ends before
        ``start_ns`` (skipped unread), None when it is unusable (counted as skipped)."""
        end = f.tell() + length
        try:
            _, end_t, usize, crc = _CHUNK_HEAD.unpack(f.read(28))
            (clen,) = _U32.unpack(f.read(4))
            kind = f.read(clen).decode("utf-8")
            (rlen,) = _U64.unpack(f.read(8))
            if f.tell() + rlen > end:
                raise ValueError("compressed data exceeds its chunk record")
            if end_t < start_ns:
                f.seek(end)
                self.stats.chunks_read += 1
                return b""
            raw = _decompress(kind, f.read(rlen), usize)
            if len(raw) != usize:
                raise ValueError(f"decompressed {len(raw)} bytes, header says {usize}")
            if crc and zlib.crc32(raw) != crc:
                raise ValueError("chunk CRC mismatch")
        except Exception as exc:  # any decode failure means the whole chunk is unusable
            f.seek(end)
            self.stats.chunks_skipped += 1
            self.stats.note(f"chunk at byte {end - length - 9} skipped: {exc}")
            return None
        f.seek(end)
        return raw

    def _truncated(self, pos: int, what: str) -> None:
        self.stats.note(f"damaged or truncated {what} at byte {pos} of {self.size}")
        if what == "record header":
            self.stats.truncated = True

    def _resync(self, f: BinaryIO, pos: int) -> bool:
        """Find the next plausible chunk record after ``pos``; False when none is left."""
        while pos < self.size:
            f.seek(pos)
            block = f.read(RESYNC_BLOCK + 64)
            i = block.find(bytes([OP_CHUNK]))
            while i != -1 and i + 45 <= len(block):
                length = _U64.unpack_from(block, i + 1)[0]
                clen = _U32.unpack_from(block, i + 37)[0]
                kind = block[i + 41 : i + 41 + clen]
                rlen_at = i + 41 + clen
                rlen = _U64.unpack_from(block, rlen_at)[0] if rlen_at + 8 <= len(block) else -1
                if (
                    pos + i + 9 + length <= self.size
                    and kind in (b"", b"zstd", b"lz4")
                    and length == 40 + clen + rlen
                ):
                    f.seek(pos + i)
                    self.stats.resyncs += 1
                    return True
                i = block.find(bytes([OP_CHUNK]), i + 1)
            if len(block) <= 64:
                break
            pos += RESYNC_BLOCK
        self.stats.truncated = True
        return False
