"""Ranges of the planner's numeric parameters, each with the reason for its bounds.

`check_number` returns the reason a value is refused (None when accepted); `require_number`
raises `ParameterError`. The node, the CLI and the fleet runner share these bounds.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import ParameterError


@dataclass(frozen=True)
class Range:
    """Accepted closed interval of one parameter and why it is bounded so."""

    lowest: float
    highest: float
    unit: str
    why: str
    integer: bool = False


RANGES: dict[str, Range] = {
    "rta_tolerance_s": Range(
        0.0, 86400.0, "s", "an arrival up to a day after the RTA may count as on time, not "
        "more; 0 means exactly on time"),
    "stage_hours": Range(
        0.1, 24.0, "h", "0 derives it from the voyage; forecasts are 1-6 hourly and a storm "
        "crosses a 12 h stage in 12 h, so longer stages sample the weather too sparsely; under "
        "6 minutes a stage is shorter than the ship's turn"),
    "budget_s": Range(
        0.05, 3600.0, "s", "a plan needs a few generations (> 50 ms) and must arrive before "
        "the next forecast cycle (< 1 h)"),
    "rng_seed": Range(0, 2**63 - 1, "", "numpy's generator takes a non-negative integer",
                      integer=True),
    "replan_cross_track_nm": Range(
        0.1, 500.0, "NM", "below 0.1 NM GNSS noise re-plans; above 500 NM the ship is on "
        "another route"),
    "replan_schedule_h": Range(
        0.05, 240.0, "h", "3 minutes is the resolution of the schedule; 10 days the length "
        "of an ocean passage"),
    "min_replan_interval_s": Range(
        0.0, 7 * 86400.0, "s", "0 re-plans at every deviation; more than a week never"),
    "departure_radius_nm": Range(
        0.0, 100.0, "NM", "a port's approaches lie within 100 NM of it"),
    "ship_state_max_age_h": Range(
        0.01, 366 * 24.0, "h", "a fix older than a year (a replayed voyage at most) is a "
        "corrupt or unset stamp"),
    "ship_state_max_lead_h": Range(
        0.0, 24.0, "h", "a fix from the future is a clock error; an hour covers clock skew"),
    "ukc_margin_m": Range(
        0.0, 10.0, "m", "UKC policies ask 0.3-2 m on top of squat and wave allowance; above "
        "10 m the check would close shelf seas and every port approach"),
    "clearance_nm": Range(
        0.0, 50.0, "NM", "beyond 50 NM from land the Dover Strait, Malacca and every port "
        "approach become impassable"),
    "open_sea_clearance_nm": Range(
        0.0, 5.0, "NM", "open-sea passages keep about 2 NM; beyond 5 NM straits such as "
        "Dover and Gibraltar close"),
    "approach_clearance_nm": Range(
        0.0, 3.0, "NM", "approaches and narrow straits keep about 0.5 NM; beyond 3 NM "
        "most port approaches close"),
    "approach_zone_nm": Range(
        0.0, 200.0, "NM", "the approach clearance applies near the span ends; 200 NM "
        "covers the longest approach"),
    "persistence_hours": Range(
        0.0, 240.0, "h", "a forecast's last fields say little of the weather days later; "
        "beyond 10 days give a climatology instead"),
    "p_hs_max": Range(0.0, 1.0, "", "a probability (member weight): 0 asks every member to "
                      "keep Hs within the ship's limit, 1 accepts any"),
    "p_late_max": Range(0.0, 1.0, "", "a probability (member weight): 0 asks every member to "
                        "arrive on time, 1 accepts any"),
    "budget_evaluations": Range(
        1, 72_000_000, "evaluations", "a plan needs at least one evaluation; 72 M is the "
        "hour of the wall-time budget's limit at 20,000 evaluations/s", integer=True),
}


def check_number(name: str, value: object, label: str = "") -> str | None:
    """Why `value` is refused for numeric parameter `name` (None: accepted or not numeric);
    the reason names `label` (e.g. the CLI option) when given, else the parameter."""
    rule = RANGES.get(name)
    if rule is None:
        return None
    label = label or name
    if isinstance(value, bool) or not isinstance(value, int | float):
        return f"{label} must be a number, got {value!r}"
    if rule.integer and not isinstance(value, int):
        return f"{label} must be an integer, got {value!r}"
    if not (math.isfinite(value) and rule.lowest <= value <= rule.highest):
        return (f"{label} = {value!r} is outside {rule.lowest:g}..{rule.highest:g} "
                f"{rule.unit}".rstrip() + f": {rule.why}")
    return None


def require_number(name: str, value: object) -> float:
    """`value` as a float, or ParameterError with the range and its reason."""
    reason = check_number(name, value)
    if reason is not None:
        raise ParameterError(reason)
    return float(value)  # type: ignore[arg-type]
