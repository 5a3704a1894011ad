"""One cycle's serialized ForecastSlice messages in an unlinked temporary file, between the load
and the publication: the weather node never holds the encoded cycle in memory beside the
middleware's history of it, so a load costs one cycle of resident memory (that history), not two.

The file is created with O_TMPFILE semantics (`tempfile.TemporaryFile`): it has no name, holds
one cycle's wire bytes on disk (the 16-day storm: ~140 MB) and is gone when closed or when the
process dies. Slices are read back one at a time and published as serialized bytes
(`Publisher.publish(bytes)`), with the header stamp set to the moment of publication.
"""

from __future__ import annotations

import os
import struct
import tempfile
from typing import Any

from rclpy.serialization import serialize_message

from shiproute_msgs.msg import ForecastSlice

from ..errors import SpoolError
from .convert import wire_bytes

#: CDR encapsulation identifiers (first two bytes of a serialized message) and the byte order
_BYTE_ORDER = {b"\x00\x00": ">", b"\x00\x01": "<"}
#: ForecastSlice's first field is std_msgs/Header, whose first field is its stamp: int32 sec,
#: uint32 nanosec, right after the 4-byte encapsulation header (both 4-byte aligned)
_STAMP_OFFSET = 4


def restamped(data: bytes | bytearray, sec: int, nanosec: int) -> bytes:
    """A serialized ForecastSlice (CDR, either byte order) with header.stamp replaced."""
    order = _BYTE_ORDER.get(bytes(data[:2]))
    if order is None or len(data) < _STAMP_OFFSET + 8:
        raise SpoolError(f"not a CDR-serialized message (encapsulation {bytes(data[:4])!r})")
    buf = data if isinstance(data, bytearray) else bytearray(data)
    struct.pack_into(f"{order}iI", buf, _STAMP_OFFSET, int(sec), int(nanosec))
    return bytes(buf)


class SliceSpool:
    """Append-only store of one cycle's serialized slices, read back one at a time."""

    def __init__(self, directory: str = "") -> None:
        try:
            # the file lives as long as the spool (closed by close()), not one block
            self._file = tempfile.TemporaryFile(dir=directory or None,  # noqa: SIM115
                                                prefix="shiproute-slices-")
        except OSError as exc:
            raise SpoolError(f"no slice spool file in {directory or tempfile.gettempdir()}: "
                             f"{exc}") from exc
        self._spans: list[tuple[int, int]] = []  # (offset, size) of each slice in the file
        self._end = 0

    def append(self, msg: ForecastSlice) -> int:
        """Serialize `msg` to the end of the file; its serialized size [bytes]."""
        data = serialize_message(msg)
        try:
            written = os.pwrite(self._file.fileno(), data, self._end)
        except OSError as exc:
            raise SpoolError(f"slice {len(self._spans)} not spooled: {exc}") from exc
        if written != len(data):
            raise SpoolError(f"slice {len(self._spans)} not spooled: {written} of "
                             f"{len(data)} bytes written")
        self._spans.append((self._end, len(data)))
        self._end += len(data)
        return len(data)

    def __len__(self) -> int:
        return len(self._spans)

    @property
    def nbytes(self) -> int:
        """Serialized bytes of all slices in the spool."""
        return self._end

    def serialized(self, index: int, sec: int, nanosec: int) -> bytes:
        """Slice `index` as serialized bytes, its header stamped (`sec`, `nanosec`)."""
        offset, size = self._spans[index]
        buf = bytearray(size)
        got = os.preadv(self._file.fileno(), [buf], offset)
        if got != size:
            raise SpoolError(f"slice {index}: {got} of {size} bytes read back")
        return restamped(buf, sec, nanosec)

    def close(self) -> None:
        """Close (and so delete) the file."""
        self._file.close()


def spool_slice(spool: SliceSpool, msg: ForecastSlice, publication: str) -> int:
    """Store one encoded slice of publication `publication`; its bytes of field values."""
    msg.publication_id = publication
    spool.append(msg)
    return wire_bytes(msg)


def publish_spooled(publisher: Any, spool: SliceSpool, stamp: Any) -> None:
    """Publish every slice of `spool` in order, stamped `stamp` (a builtin_interfaces Time),
    one serialized slice at a time."""
    for k in range(len(spool)):
        publisher.publish(spool.serialized(k, stamp.sec, stamp.nanosec))
