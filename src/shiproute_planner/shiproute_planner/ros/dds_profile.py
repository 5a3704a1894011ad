"""Fast DDS settings of the planner process: release each forecast slice as soon as it is taken.

rmw_fastrtps keeps a reader's received payloads in a pool for reuse (history memory policy
PREALLOCATED_WITH_REALLOC), so after one cycle the planner would hold ~130 x 1.4 MB of slice
buffers for good. A profile for the slice topic with the DYNAMIC policy frees them instead;
every other endpoint keeps rmw_fastrtps' own defaults (PREALLOCATED_WITH_REALLOC, asynchronous
publishing). Nothing is changed when the integrator configures Fast DDS through XML already.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from pathlib import Path

_PROFILE = """<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns="http://www.eprosima.com">
  <profiles>
    <data_writer profile_name="shiproute planner writers" is_default_profile="true">
      <qos><publishMode><kind>ASYNCHRONOUS</kind></publishMode></qos>
      <historyMemoryPolicy>PREALLOCATED_WITH_REALLOC</historyMemoryPolicy>
    </data_writer>
    <data_reader profile_name="shiproute planner readers" is_default_profile="true">
      <historyMemoryPolicy>PREALLOCATED_WITH_REALLOC</historyMemoryPolicy>
    </data_reader>
    <data_reader profile_name="{topic}">
      <historyMemoryPolicy>DYNAMIC</historyMemoryPolicy>
    </data_reader>
  </profiles>
</dds>
"""
_USER_SETTINGS = ("FASTDDS_DEFAULT_PROFILES_FILE", "FASTRTPS_DEFAULT_PROFILES_FILE",
                  "RMW_FASTRTPS_USE_QOS_FROM_XML")


def use_dynamic_slice_buffers(slices_topic: str) -> Path | None:
    """Point Fast DDS at a profile freeing `slices_topic` payloads once taken (call before
    rclpy.init). Returns the profile file, or None when the environment configures Fast DDS."""
    if any(os.environ.get(name) for name in _USER_SETTINGS):
        return None
    fd, name = tempfile.mkstemp(prefix="shiproute-planner-dds-", suffix=".xml")
    with os.fdopen(fd, "w") as f:
        f.write(_PROFILE.format(topic=slices_topic))
    os.environ["FASTDDS_DEFAULT_PROFILES_FILE"] = name
    os.environ["RMW_FASTRTPS_USE_QOS_FROM_XML"] = "1"
    return Path(name)


def forget_profile(path: Path | None) -> None:
    """Remove the profile file and its environment settings once the node exists (Fast DDS
    reads the file once, when the process's participant is created; children must not)."""
    if path is None:
        return
    with contextlib.suppress(OSError):
        path.unlink()
    for name in ("FASTDDS_DEFAULT_PROFILES_FILE", "RMW_FASTRTPS_USE_QOS_FROM_XML"):
        os.environ.pop(name, None)
