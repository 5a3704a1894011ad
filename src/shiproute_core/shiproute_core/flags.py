"""Constraint flags of a plan: the bit values of shiproute_msgs/RoutePlan FLAG_* (one definition;
a test checks them against the .msg) and the words a plan uses for each."""

from __future__ import annotations

FLAG_LAND = 1
FLAG_RTA = 2
FLAG_SLAMMING = 4
FLAG_DECK_WETNESS = 8
FLAG_PROPELLER_EMERGENCE = 16
FLAG_HEADING_CHANGE = 32
FLAG_RPM_RANGE = 64
FLAG_WAVE_LIMIT = 128
FLAG_WIND_LIMIT = 256
FLAG_IMO_SURF_RIDING = 512
FLAG_IMO_PARAMETRIC_ROLL = 1024
FLAG_IMO_SYNCHRONOUS_ROLL = 2048
FLAG_IMO_HIGH_WAVE_GROUP = 4096
FLAG_DEPTH = 8192
FLAG_ENGINE_LIMIT = 16384
FLAG_LATITUDE = 32768  # planner-internal: a node beyond the latitude bound (not in the .msg)
FLAG_NO_GO_ZONE = 65536

PLANNER_INTERNAL_FLAGS = frozenset({"FLAG_LATITUDE"})

FLAG_NAMES = {
    FLAG_LAND: "crosses land",
    FLAG_RTA: "arrives after the RTA",
    FLAG_SLAMMING: "slamming probability above criterion",
    FLAG_DECK_WETNESS: "deck wetness probability above criterion",
    FLAG_PROPELLER_EMERGENCE: "propeller emergence probability above criterion",
    FLAG_HEADING_CHANGE: "heading change above the per-stage limit",
    FLAG_RPM_RANGE: "RPM outside the engine range",
    FLAG_WAVE_LIMIT: "significant wave height above the ship limit",
    FLAG_WIND_LIMIT: "wind speed above the ship limit",
    FLAG_IMO_SURF_RIDING: "IMO surf-riding/broaching risk",
    FLAG_IMO_PARAMETRIC_ROLL: "IMO parametric roll risk",
    FLAG_IMO_SYNCHRONOUS_ROLL: "IMO synchronous roll risk",
    FLAG_IMO_HIGH_WAVE_GROUP: "IMO successive high-wave attack risk",
    FLAG_DEPTH: "under-keel clearance below limit",
    FLAG_ENGINE_LIMIT: "engine overload",
    FLAG_LATITUDE: "beyond the latitude bound",
    FLAG_NO_GO_ZONE: "enters a no-go zone",
}


def describe_flags(flags: int) -> list[str]:
    """Human-readable reasons for a plan's flag bitmask."""
    return [text for bit, text in FLAG_NAMES.items() if flags & bit]
