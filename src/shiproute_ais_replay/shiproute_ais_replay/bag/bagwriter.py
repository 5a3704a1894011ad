"""Write rosbag2 MCAP bags: a directory with ``metadata.yaml`` + ``<name>.mcap``, or a bare .mcap.

Built on the ``mcap`` writer (zstd chunks with CRCs, chunk and message indexes, summary with
schemas and channels) so rosbags, Foxglove and ``mcap`` all open the result; message
definitions come from the rosbags typestore and are embedded as ``ros2msg`` schemas.
"""

from __future__ import annotations

from pathlib import Path
from types import TracebackType
from typing import Any

import yaml
from mcap.writer import CompressionType, Writer
from rosbags.typesys.store import Typestore

from ..errors import BagWriteError
from .typestore import build_typestore, msgdef

DEFAULT_CHUNK_BYTES = 1 << 20


def qos_yaml(reliability: str = "reliable", durability: str = "volatile", depth: int = 10) -> str:
    """Offered-QoS profile list as rosbag2 (metadata version 9) stores it in channel metadata."""
    zero = {"sec": 0, "nsec": 0}
    return yaml.safe_dump([{
        "history": "keep_last", "depth": depth, "reliability": reliability,
        "durability": durability, "deadline": zero, "lifespan": zero,
        "liveliness": "automatic", "liveliness_lease_duration": zero,
        "avoid_ros_namespace_conventions": False,
    }], sort_keys=False)


class BagWriter:
    """Streaming writer: ``add_topic`` once per topic, then ``write`` (or ``write_message``)."""

    def __init__(
        self,
        path: str | Path,
        store: Typestore | None = None,
        chunk_bytes: int = DEFAULT_CHUNK_BYTES,
        compress: bool = True,
    ) -> None:
        self.path = Path(path)
        self.store = store if store is not None else build_typestore()
        if self.path.exists():
            raise BagWriteError(f"bag output {self.path} exists already; not overwriting")
        self.bare = self.path.suffix == ".mcap"
        if self.bare:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            self.mcap_path = self.path
        else:
            self.path.mkdir(parents=True)
            self.mcap_path = self.path / f"{self.path.name}.mcap"
        self._file = self.mcap_path.open("xb")
        comp = CompressionType.ZSTD if compress else CompressionType.NONE
        self._writer = Writer(self._file, chunk_size=chunk_bytes, compression=comp)
        self._writer.start(profile="ros2", library="shiproute_ais_replay")
        self._schemas: dict[str, int] = {}
        self._topics: dict[str, tuple[int, str]] = {}
        self._counts: dict[str, int] = {}
        self._qos: dict[str, list] = {}  # metadata.yaml must repeat the channel's QoS list
        self._t_min_ns = 2**63 - 1
        self._t_max_ns = 0
        self._closed = False

    def add_topic(self, topic: str, typename: str, qos_yaml: str = "[]") -> None:
        """Declare a topic with its message type (definition embedded from the typestore)."""
        if topic in self._topics:
            if self._topics[topic][1] != typename:
                raise BagWriteError(
                    f"topic {topic} already has type {self._topics[topic][1]}, not {typename}"
                )
            return
        if typename not in self._schemas:
            text = msgdef(self.store, typename)
            self._schemas[typename] = self._writer.register_schema(
                name=typename, encoding="ros2msg", data=text.encode()
            )
        chan = self._writer.register_channel(
            topic=topic,
            message_encoding="cdr",
            schema_id=self._schemas[typename],
            metadata={"offered_qos_profiles": qos_yaml},
        )
        self._topics[topic] = (chan, typename)
        self._qos[topic] = yaml.safe_load(qos_yaml) or []
        self._counts[topic] = 0

    def write(self, topic: str, time_ns: int, data: bytes | memoryview) -> None:
        """Append one serialized CDR message received/recorded at ``time_ns`` (POSIX ns)."""
        if self._closed:
            raise BagWriteError(f"bag {self.path} is closed; cannot write to {topic}")
        try:
            chan = self._topics[topic][0]
        except KeyError:
            raise BagWriteError(f"topic {topic} was not added to bag {self.path}") from None
        self._writer.add_message(chan, log_time=time_ns, data=bytes(data), publish_time=time_ns)
        self._counts[topic] += 1
        self._t_min_ns = min(self._t_min_ns, time_ns)
        self._t_max_ns = max(self._t_max_ns, time_ns)

    def write_message(self, topic: str, time_ns: int, msg: Any) -> None:
        """Serialize a rosbags message object to CDR and append it."""
        self.write(topic, time_ns, self.store.serialize_cdr(msg, self._topics[topic][1]))

    @property
    def counts(self) -> dict[str, int]:
        """Messages written per topic so far."""
        return dict(self._counts)

    def close(self) -> None:
        """Write the MCAP summary and (for bag directories) metadata.yaml."""
        if self._closed:
            return
        self._closed = True
        self._writer.finish()
        self._file.close()
        if not self.bare:
            (self.path / "metadata.yaml").write_text(self._metadata_yaml(), encoding="utf-8")

    def _metadata_yaml(self) -> str:
        total = sum(self._counts.values())
        start = self._t_min_ns if total else 0
        duration = max(0, self._t_max_ns - self._t_min_ns) if total else 0
        topics = [
            {
                "topic_metadata": {
                    "name": topic,
                    "type": typename,
                    "serialization_format": "cdr",
                    "offered_qos_profiles": self._qos[topic],
                    "type_description_hash": self.store.hash_rihs01(typename),
                },
                "message_count": self._counts[topic],
            }
            for topic, (_, typename) in self._topics.items()
        ]
        info = {
            "version": 9,
            "storage_identifier": "mcap",
            "relative_file_paths": [self.mcap_path.name],
            "duration": {"nanoseconds": duration},
            "starting_time": {"nanoseconds_since_epoch": start},
            "message_count": total,
            "topics_with_message_count": topics,
            "compression_format": "",
            "compression_mode": "",
            "files": [
                {
                    "path": self.mcap_path.name,
                    "starting_time": {"nanoseconds_since_epoch": start},
                    "duration": {"nanoseconds": duration},
                    "message_count": total,
                }
            ],
            "custom_data": None,
            "ros_distro": "kilted",
        }
        return yaml.safe_dump({"rosbag2_bagfile_information": info}, sort_keys=False)

    def __enter__(self) -> BagWriter:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()
