"""The planner node's `port_calls` parameter: port calls as one ';'-separated string of
`PORT[@EARLIEST..LATEST][+BERTH_H]` items with ISO UTC times (ROS-free)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

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


def calls_ahead(calls: Sequence[PortCall], previous: Any, now_s: float | None
                ) -> tuple[PortCall, ...]:
    """The calls still ahead of a ship under way: those the previous plan had it leave
    before `now_s` are done (a re-plan from the ship's position must not go back)."""
    if previous is None or now_s is None:
        return tuple(calls)
    left = {str(r["port"]).casefold() for r in previous.extra.get("port_calls", ())
            if float(r.get("departure_s", float("inf"))) <= now_s}
    return tuple(c for c in calls if c.port.casefold() not in left)
