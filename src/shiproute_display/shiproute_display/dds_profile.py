"""Fast DDS settings of the display process: take a forecast cycle in small steps.

A cycle reaches a subscriber as one burst (129 slices of ~0.7 MB in a fraction of a second),
and a keep-last reader deep enough to hold the whole cycle for a late joiner holds all of it
in memory until the (slower) callbacks have taken each slice: ~90 MB on top of the node. The
display's slice reader is therefore keep-all with room for `SLICE_WINDOW` samples: a full
reader does not acknowledge, so the reliable writer holds the rest and resends it as room
frees up (no slice is lost; the cycle arrives over seconds instead of at once, which the page
does not mind), and payloads are freed once taken (DYNAMIC). Every other endpoint keeps
rmw_fastrtps' defaults. Nothing is changed when the integrator configures Fast DDS with XML.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from pathlib import Path

SLICE_WINDOW = 12  #: slices the display's reader holds at most

_PROFILE = """<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns="http://www.eprosima.com">
  <profiles>
    <data_writer profile_name="shiproute display writers" is_default_profile="true">
      <qos><publishMode><kind>ASYNCHRONOUS</kind></publishMode></qos>
      <historyMemoryPolicy>PREALLOCATED_WITH_REALLOC</historyMemoryPolicy>
    </data_writer>
    <data_reader profile_name="shiproute display readers" is_default_profile="true">
      <historyMemoryPolicy>PREALLOCATED_WITH_REALLOC</historyMemoryPolicy>
    </data_reader>
    <data_reader profile_name="{topic}">
      <topic>
        <historyQos><kind>KEEP_ALL</kind></historyQos>
        <resourceLimitsQos>
          <max_samples>{window}</max_samples>
          <max_instances>1</max_instances>
          <max_samples_per_instance>{window}</max_samples_per_instance>
          <allocated_samples>{window}</allocated_samples>
        </resourceLimitsQos>
      </topic>
      <qos>
        <durability><kind>TRANSIENT_LOCAL</kind></durability>
        <reliability><kind>RELIABLE</kind></reliability>
      </qos>
      <historyMemoryPolicy>DYNAMIC</historyMemoryPolicy>
    </data_reader>
  </profiles>
</dds>
"""
_USER_SETTINGS = ("FASTDDS_DEFAULT_PROFILES_FILE", "FASTRTPS_DEFAULT_PROFILES_FILE",
                  "RMW_FASTRTPS_USE_QOS_FROM_XML")


def use_windowed_slice_reader(slices_topic: str) -> Path | None:
    """Point Fast DDS at the profile above (call before rclpy.init). Returns the profile file,
    or None when the environment configures Fast DDS already."""
    if any(os.environ.get(name) for name in _USER_SETTINGS):
        return None
    fd, name = tempfile.mkstemp(prefix="shiproute-display-dds-", suffix=".xml")
    with os.fdopen(fd, "w") as f:
        f.write(_PROFILE.format(topic=slices_topic, window=SLICE_WINDOW))
    os.environ["FASTDDS_DEFAULT_PROFILES_FILE"] = name
    os.environ["RMW_FASTRTPS_USE_QOS_FROM_XML"] = "1"
    return Path(name)


def forget_profile(path: Path | None) -> None:
    """Remove the profile file and its environment settings once the node exists."""
    if path is None:
        return
    with contextlib.suppress(OSError):
        path.unlink()
    for name in ("FASTDDS_DEFAULT_PROFILES_FILE", "RMW_FASTRTPS_USE_QOS_FROM_XML"):
        os.environ.pop(name, None)
