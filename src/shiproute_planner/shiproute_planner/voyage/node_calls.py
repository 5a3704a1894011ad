"""The planner node's `port_calls` parameter: port calls as one ';'-separated string of
`PORT[@EARLIEST..LATEST][+BERTH_H]` items with ISO UTC times (ROS-free)."""

from __future__ import annotations

from collections.abc import Sequence

from ..errors import PlannerError
from .port_calls import PortCall, parse_port_call


def node_port_calls(text: str, depart_s: float) -> tuple[PortCall, ...]:
    """The parameter's port calls (offsets, if any, count from `depart_s`)."""
    return tuple(parse_port_call(item, depart_s) for item in text.split(";") if item.strip())


def port_calls_parameter(calls: Sequence[PortCall]) -> str:
    """Port calls -> the parameter's text (ISO UTC times to the second)."""
    return ";".join(c.label() for c in calls)


def port_calls_reason(text: str) -> str | None:
    """Why `text` is no valid `port_calls` parameter, or None when it is."""
    try:
        node_port_calls(str(text), 0.0)
    except PlannerError as exc:
        return f"port_calls: {exc}"
    return None
