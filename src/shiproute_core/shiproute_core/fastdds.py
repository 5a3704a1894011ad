"""A per-process Fast DDS profile for the forecast-slice reader, written once for every node.

rmw_fastrtps reads an XML profile file named in the environment when the process's participant
is created. A node that needs its own settings for one reader (the forecast slices) writes a
profile keeping rmw_fastrtps' defaults for every other endpoint (asynchronous writers,
PREALLOCATED_WITH_REALLOC history memory) plus one `<data_reader>` named after that topic,
points Fast DDS at it before rclpy.init and forgets it once the node exists. Nothing is changed
when the integrator configures Fast DDS through XML already.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from pathlib import Path

PROFILE_TEMPLATE = """<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns="http://www.eprosima.com">
  <profiles>
    <data_writer profile_name="shiproute {process} writers" is_default_profile="true">
      <qos><publishMode><kind>ASYNCHRONOUS</kind></publishMode></qos>
      <historyMemoryPolicy>PREALLOCATED_WITH_REALLOC</historyMemoryPolicy>
    </data_writer>
    <data_reader profile_name="shiproute {process} readers" is_default_profile="true">
      <historyMemoryPolicy>PREALLOCATED_WITH_REALLOC</historyMemoryPolicy>
    </data_reader>
    <data_reader profile_name="{topic}">
{reader_settings}
    </data_reader>
  </profiles>
</dds>
"""
USER_SETTINGS = ("FASTDDS_DEFAULT_PROFILES_FILE", "FASTRTPS_DEFAULT_PROFILES_FILE",
                 "RMW_FASTRTPS_USE_QOS_FROM_XML")
_SET_HERE = ("FASTDDS_DEFAULT_PROFILES_FILE", "RMW_FASTRTPS_USE_QOS_FROM_XML")


def profile_xml(process: str, topic: str, reader_settings: str) -> str:
    """The profile document: rmw_fastrtps' defaults plus `reader_settings` for `topic`."""
    return PROFILE_TEMPLATE.format(process=process, topic=topic,
                                   reader_settings=reader_settings.rstrip("\n"))


def use_topic_reader_profile(process: str, topic: str, reader_settings: str) -> Path | None:
    """Write the profile to a temporary file and point Fast DDS at it (call before rclpy.init).
    Returns the file, or None when the environment configures Fast DDS already."""
    if any(os.environ.get(name) for name in USER_SETTINGS):
        return None
    fd, name = tempfile.mkstemp(prefix=f"shiproute-{process}-dds-", suffix=".xml")
    with os.fdopen(fd, "w") as f:
        f.write(profile_xml(process, topic, reader_settings))
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
    for name in _SET_HERE:
        os.environ.pop(name, None)
