"""Quality of service of the planner node's streams, chosen per stream."""

from __future__ import annotations

from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

#: plans: the last one is kept for late joiners (a display started after the plan)
LATCHED = QoSProfile(
    depth=1,
    history=HistoryPolicy.KEEP_LAST,
    reliability=ReliabilityPolicy.RELIABLE,
    durability=DurabilityPolicy.TRANSIENT_LOCAL,
)
#: forecast slices: a whole cycle's history, so a late planner still gets every slice
SLICES = QoSProfile(
    depth=512,
    history=HistoryPolicy.KEEP_LAST,
    reliability=ReliabilityPolicy.RELIABLE,
    durability=DurabilityPolicy.TRANSIENT_LOCAL,
)
#: the reader keeps several announcements: with depth 1 one that arrives while the intake is
#: busy packing the previous cycle's slices is overwritten, and its cycle never completes
ANNOUNCEMENTS = QoSProfile(
    depth=8,
    history=HistoryPolicy.KEEP_LAST,
    reliability=ReliabilityPolicy.RELIABLE,
    durability=DurabilityPolicy.TRANSIENT_LOCAL,
)
#: ship states: reliable, a short queue
STATE = QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE)
