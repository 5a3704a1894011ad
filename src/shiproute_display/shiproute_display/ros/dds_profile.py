"""Fast DDS settings of the display process: take a forecast cycle in small steps.

A cycle reaches a subscriber as one burst (every slice of a cycle within a fraction of a
second), and a keep-last reader deep enough to hold the whole cycle for a late joiner holds all
of it in memory until the (slower) callbacks have taken each slice. The display's slice reader
is therefore keep-all with room for `SLICE_WINDOW` samples: a full reader does not acknowledge,
so the reliable writer holds the rest and resends it as room frees up (no slice is lost; the
cycle arrives over seconds instead of at once, which the page does not mind), and payloads are
freed once taken (DYNAMIC). Every other endpoint keeps rmw_fastrtps' defaults
(shiproute_core.fastdds writes the profile).
"""

from __future__ import annotations

from pathlib import Path

from shiproute_core.fastdds import forget_profile, use_topic_reader_profile

__all__ = ["SLICE_WINDOW", "forget_profile", "use_windowed_slice_reader"]

SLICE_WINDOW = 12  #: slices the display's reader holds at most

_READER_SETTINGS = """\
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
"""


def use_windowed_slice_reader(slices_topic: str) -> Path | None:
    """Point Fast DDS at the display's profile (call before rclpy.init). Returns the profile
    file, or None when the environment configures Fast DDS already."""
    return use_topic_reader_profile("display", slices_topic,
                                    _READER_SETTINGS.format(window=SLICE_WINDOW))
