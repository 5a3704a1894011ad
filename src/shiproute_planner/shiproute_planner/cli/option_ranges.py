"""The CLI's numeric options checked against the planner node's parameter ranges.

One table (`checks.parameters.RANGES`) bounds a setting whether it arrives as a node parameter,
a fleet row or a command-line option; here each option is mapped to its parameter, and a
refusal names the option as the user typed it, its valid range and the reason.
"""

from __future__ import annotations

import argparse

from ..checks.parameters import check_number
from ..errors import InvalidVoyageError, ParameterError
from ..plan_request import Budget, duration_s
from ..route.risk import RiskSpec, parse_risk

#: option -> (argparse destination, parameter of the range table)
PLAN_OPTIONS: dict[str, tuple[str, str]] = {
    "--stage-hours": ("stage_hours", "stage_hours"),
    "--seed": ("seed", "rng_seed"),
    "--ukc-margin": ("ukc_margin", "ukc_margin_m"),
    "--clearance-nm": ("clearance_nm", "clearance_nm"),
    "--open-sea-clearance-nm": ("open_sea_clearance_nm", "open_sea_clearance_nm"),
    "--approach-clearance-nm": ("approach_clearance_nm", "approach_clearance_nm"),
    "--approach-zone-nm": ("approach_zone_nm", "approach_zone_nm"),
    "--persistence-hours": ("persistence_hours", "persistence_hours"),
    "--p-hs-max": ("p_hs_max", "p_hs_max"),
    "--p-late-max": ("p_late_max", "p_late_max"),
}
CHECK_OPTIONS: dict[str, tuple[str, str]] = {
    "--ukc-margin": ("ukc_margin", "ukc_margin_m"),
    "--clearance-nm": ("clearance_nm", "clearance_nm"),
}


def budget_number(text: str) -> tuple[str, float]:
    """(range-table parameter, value) of a --budget text: evaluations or wall seconds.

    A wall time the budget parser refuses (zero, negative) is still returned as a number, so
    the refusal states the valid range; text that is no budget at all raises its own error."""
    try:
        budget = Budget.parse(text)
    except InvalidVoyageError as refused:
        negative = str(text).strip().startswith("-")
        try:
            wall = duration_s(str(text).strip().lstrip("-"))
        except InvalidVoyageError:
            raise ParameterError(f"--budget: {refused}") from None
        return "budget_s", -wall if negative else wall
    if budget.evaluations:
        return "budget_evaluations", budget.evaluations
    return "budget_s", budget.wall_s


def check_options(args: argparse.Namespace, options: dict[str, tuple[str, str]],
                  budget_option: str = "") -> None:
    """Raise ParameterError for the first option outside its parameter's range."""
    values: list[tuple[str, str, object]] = [
        (option, parameter, getattr(args, dest)) for option, (dest, parameter) in options.items()
        if getattr(args, dest) is not None]  # None: the option was left to its derived default
    if budget_option:
        text = getattr(args, budget_option.lstrip("-"))
        if text is not None:  # None: the command's default budget
            parameter, number = budget_number(text)
            values.append((budget_option, parameter, number))
    for option, parameter, value in values:
        reason = check_number(parameter, value, label=option)
        if reason is not None:
            raise ParameterError(reason)


def risk_option(measure: str | None, p_hs_max: float | None,
                p_late_max: float | None) -> RiskSpec | None:
    """The `--risk` measure with its chance bounds (None: no --risk), or ParameterError
    naming the option; a bound without --risk is refused (it would be silently ignored)."""
    if measure is None:
        for option, value in (("--p-hs-max", p_hs_max), ("--p-late-max", p_late_max)):
            if value is not None:
                raise ParameterError(f"{option} needs --risk (mean, cvar:ALPHA or worst)")
        return None
    try:
        return parse_risk(measure, p_hs_max, p_late_max)
    except ParameterError as exc:
        text = str(exc).replace("p_hs_max", "--p-hs-max").replace("p_late_max", "--p-late-max")
        raise ParameterError(f"--risk: {text}" if text.startswith("risk") else text) from None
