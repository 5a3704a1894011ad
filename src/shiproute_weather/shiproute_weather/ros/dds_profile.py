"""Fast DDS settings of the weather node: the slice writer's payloads sized per sample.

rmw_fastrtps' default history memory (PREALLOCATED_WITH_REALLOC) keeps each history slot at the
largest payload it ever held. The slice writer's history is `max_slices` deep and its cycles
differ in slice count and size (an ensemble: 200 slices of 180 kB; the deterministic storm:
129 of 713 kB), so a node alternating them kept slots for the larger count at the larger size.
The slice writer's history is therefore DYNAMIC (each payload allocated for its sample and freed
with it); every other endpoint keeps rmw_fastrtps' defaults, and the QoS set in code (depth,
reliability, durability) still applies. Nothing is changed when Fast DDS is configured by XML
already (`shiproute_core.fastdds.USER_SETTINGS`).
"""

from __future__ import annotations

from pathlib import Path

from shiproute_core.fastdds import forget_profile, use_topic_profile

__all__ = ["forget_profile", "use_dynamic_slice_writer"]

#: the slice writer's settings: asynchronous like every writer, payloads sized per sample
SLICE_WRITER_SETTINGS = """      <qos><publishMode><kind>ASYNCHRONOUS</kind></publishMode></qos>
      <historyMemoryPolicy>DYNAMIC</historyMemoryPolicy>"""


def use_dynamic_slice_writer(slices_topic: str) -> Path | None:
    """Point Fast DDS at the weather node's profile (call before rclpy.init). Returns the
    profile file, or None when the environment configures Fast DDS already."""
    return use_topic_profile("weather", slices_topic, SLICE_WRITER_SETTINGS, "data_writer")
