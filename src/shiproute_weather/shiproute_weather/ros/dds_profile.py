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

import os
import tempfile
from pathlib import Path

from shiproute_core.fastdds import USER_SETTINGS, forget_profile

__all__ = ["forget_profile", "use_dynamic_slice_writer"]

_PROFILE = """<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns="http://www.eprosima.com">
  <profiles>
    <data_writer profile_name="shiproute weather writers" is_default_profile="true">
      <qos><publishMode><kind>ASYNCHRONOUS</kind></publishMode></qos>
      <historyMemoryPolicy>PREALLOCATED_WITH_REALLOC</historyMemoryPolicy>
    </data_writer>
    <data_reader profile_name="shiproute weather readers" is_default_profile="true">
      <historyMemoryPolicy>PREALLOCATED_WITH_REALLOC</historyMemoryPolicy>
    </data_reader>
    <data_writer profile_name="{topic}">
      <qos><publishMode><kind>ASYNCHRONOUS</kind></publishMode></qos>
      <historyMemoryPolicy>DYNAMIC</historyMemoryPolicy>
    </data_writer>
  </profiles>
</dds>
"""


def use_dynamic_slice_writer(slices_topic: str) -> Path | None:
    """Point Fast DDS at the weather node's profile (call before rclpy.init). Returns the
    profile file, or None when the environment configures Fast DDS already."""
    if any(os.environ.get(name) for name in USER_SETTINGS):
        return None
    fd, name = tempfile.mkstemp(prefix="shiproute-weather-dds-", suffix=".xml")
    with os.fdopen(fd, "w") as f:
        f.write(_PROFILE.format(topic=slices_topic))
    os.environ["FASTDDS_DEFAULT_PROFILES_FILE"] = name
    os.environ["RMW_FASTRTPS_USE_QOS_FROM_XML"] = "1"
    return Path(name)
