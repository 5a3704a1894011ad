"""Fast DDS settings of the planner process: release each forecast slice as soon as it is taken.

rmw_fastrtps keeps a reader's received payloads in a pool for reuse (history memory policy
PREALLOCATED_WITH_REALLOC), so after one cycle the planner would hold every slice buffer of the
cycle for good. A profile for the slice topic with the DYNAMIC policy frees them instead;
every other endpoint keeps rmw_fastrtps' own defaults (shiproute_core.fastdds writes the
profile). Nothing is changed when the integrator configures Fast DDS through XML already.
"""

from __future__ import annotations

from pathlib import Path

from shiproute_core.fastdds import forget_profile, use_topic_reader_profile

__all__ = ["forget_profile", "use_dynamic_slice_buffers"]

_READER_SETTINGS = "      <historyMemoryPolicy>DYNAMIC</historyMemoryPolicy>\n"


def use_dynamic_slice_buffers(slices_topic: str) -> Path | None:
    """Point Fast DDS at a profile freeing `slices_topic` payloads once taken (call before
    rclpy.init). Returns the profile file, or None when the environment configures Fast DDS."""
    return use_topic_reader_profile("planner", slices_topic, _READER_SETTINGS)
