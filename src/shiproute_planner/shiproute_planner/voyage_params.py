"""Validation of the planner node's voyage and re-plan parameters (ROS-free).

Every check returns a reason naming the parameter and what is wrong, so the node can reject a
bad value and keep running with the old one.
"""

from __future__ import annotations

from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from .checks.forecast_wire import EARLIEST_TIME_S, LATEST_TIME_S
from .checks.parameters import check_number
from .objectives import OBJECTIVES
from .ship.fuel import CO2_FACTOR_T_PER_T


def parse_utc(text: str) -> float:
    """ISO 8601 UTC time ('Z' or an offset allowed; naive means UTC) -> POSIX seconds."""
    value = datetime.fromisoformat(text.strip().replace("Z", "+00:00"))
    if value.tzinfo is None:
        value = value.replace(tzinfo=UTC)
    return value.timestamp()


def check_parameter(name: str, value: Any) -> str | None:
    """Reason why `value` is not acceptable for parameter `name`, or None when it is."""
    if name in ("rta", "departure_time"):
        if value == "" and name == "departure_time":
            return None
        try:
            t = parse_utc(str(value))
        except (ValueError, OverflowError):
            return f"{name} must be an ISO 8601 UTC time like 2026-03-16T18:00:00Z, got {value!r}"
        if not EARLIEST_TIME_S <= t <= LATEST_TIME_S:
            return f"{name} = {value!r} is outside 1990..2100"
        return None
    if name == "objective" and value not in OBJECTIVES:
        return f"objective must be one of {', '.join(OBJECTIVES)}, got {value!r}"
    if name in ("destination", "origin") and not str(value).strip():
        return f"{name} must name a port, a UN/LOCODE or 'lat,lon'"
    if name == "ship" and not str(value).strip():
        return "ship must name a bundled ship or a ship file"
    if name == "stage_hours" and value == 0.0:
        return None  # derived from the voyage
    if name == "port_calls":
        from .voyage.node_calls import port_calls_reason

        return port_calls_reason(str(value))
    if name in ("ship_model", "risk"):
        return (_ship_model_reason if name == "ship_model" else _risk_reason)(str(value))
    if name == "fuel_type" and str(value).strip().upper() not in ("", *CO2_FACTOR_T_PER_T):
        return f"fuel_type must be '' or one of {', '.join(CO2_FACTOR_T_PER_T)}, got {value!r}"
    if name in ("fuel_price_usd_per_t", "charter_usd_per_day") and (
            isinstance(value, bool) or not isinstance(value, int | float)
            or not -1.0 <= value < 1e7):
        return f"{name} must be a number in 0..1e7 (or -1: ship file / default), got {value!r}"
    if name in ("bathymetry_files", "zones_files", "approach_files"):
        missing = [p.strip() for p in str(value).split(",") if p.strip()
                   and not Path(p.strip()).is_file()]
        if missing:
            return f"{name}: no such file {', '.join(missing)}"
    return check_number(name, value)


def _risk_reason(value: str) -> str | None:
    """Why `value` is not a risk measure ('' = none), or None."""
    from .errors import ParameterError
    from .route.risk import parse_risk

    if not value.strip():
        return None
    try:
        parse_risk(value)
    except ParameterError as exc:
        return str(exc)
    return None


def _ship_model_reason(value: str) -> str | None:
    """ship_model: '', physics, kwon, or profile:/learned: with an existing file."""
    import os

    kind, sep, path = value.strip().partition(":")
    if kind in ("", "physics", "kwon") and not sep:
        return None
    if kind in ("profile", "learned") and path:
        return None if os.path.isfile(path) else f"ship_model file {path!r} does not exist"
    return (f"ship_model must be '', physics, kwon, profile:FILE.nc or learned:FILE.nc, "
            f"got {value!r}")
