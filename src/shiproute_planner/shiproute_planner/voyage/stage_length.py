"""Stage length that fits the voyage, and the GA's moves scaled with the number of stages.

An ocean crossing is planned in 12-hour stages (the reference study's formulation); a
shorter passage gets stages short enough that its optimised part has about `TARGET_STAGES`
of them, so a 6-hour coastal passage is shaped by as many heading/RPM decisions as it needs
rather than one. The GA's heading moves act on relative headings (a change turns the whole
tail of the route), so their lateral effect grows with the number of stages behind them: the
mutation and jitter scales are divided by sqrt(n / 24), keeping the size of a move relative
to the leg the same for 10 stages as for 25.
"""

from __future__ import annotations

import dataclasses
import math

from ..errors import InvalidVoyageError
from ..ga.loop import GAConfig

OCEAN_STAGE_H = 12.0  # the reference formulation's stage for an ocean crossing
TARGET_STAGES = 12  # stages a short passage's optimised part is given at least
MIN_SPAN_STAGES = 4  # stages of a span of a leg split by a strait or canal, at least
STAGES_PER_TURN = 5  # stages per cape or strait of a leg's sea lane
MIN_STAGE_H = 0.1  # 6 minutes: below this a stage is shorter than the ship's turning
MAX_STAGE_H = 24.0  # the parameter table's bound (checks.parameters): longer stages miss storms
REFERENCE_STAGES = 24  # the GA's default move sizes were tuned on ~24-stage crossings
RTA_TOLERANCE_S = 300.0  # default: arriving within 5 minutes of the RTA is on time


def default_stage_hours(window_s: float, target: int = TARGET_STAGES) -> float:
    """Stage duration [h] for an optimised part of `window_s` seconds: 12 h for a crossing,
    shorter (down to 6 min) so a short passage still gets ~`target` stages."""
    hours = max(window_s, 0.0) / 3600.0 / (target + 1)
    return float(min(OCEAN_STAGE_H, max(MIN_STAGE_H, hours)))


def leg_stage_hours(window_s: float, lane_turns: int, target: int = TARGET_STAGES) -> float:
    """Stage duration [h] of a leg whose sea lane rounds `lane_turns` capes and straits: the
    voyage's default, shortened to STAGES_PER_TURN stages per turn (a 12-hour stage cannot
    follow the lane through the Strait of Gibraltar and up the Channel)."""
    stages = max(target, STAGES_PER_TURN * lane_turns)
    hours = max(window_s, 0.0) / 3600.0 / (stages + 1)
    return float(min(default_stage_hours(window_s, target), max(MIN_STAGE_H, hours)))


def check_stage_hours(stage_hours: float | None) -> float | None:
    """The user's stage duration [h] (None = derived), or InvalidVoyageError naming it."""
    if stage_hours is None:
        return None
    value = float(stage_hours)
    if not (math.isfinite(value) and MIN_STAGE_H <= value <= MAX_STAGE_H):
        raise InvalidVoyageError(f"stage hours {stage_hours!r}: expected {MIN_STAGE_H:g} to "
                                 f"{MAX_STAGE_H:g} h (or leave it out to derive it)")
    return value


def check_rta_tolerance_s(tolerance_s: float) -> float:
    """The RTA tolerance [s], or InvalidVoyageError when negative, not finite or > 1 day."""
    value = float(tolerance_s)
    if not (math.isfinite(value) and 0.0 <= value <= 86400.0):
        raise InvalidVoyageError(f"RTA tolerance {tolerance_s!r} s: expected 0 to 86400 s")
    return value


def move_scale(n_stages: int) -> float:
    """Factor on the GA's heading move sizes for a leg of `n_stages` stages."""
    return float(min(2.0, max(0.5, math.sqrt(REFERENCE_STAGES / max(n_stages, 1)))))


def scaled_ga_config(config: GAConfig | None, n_stages: int) -> GAConfig:
    """`config` (default GAConfig) with its heading moves scaled for `n_stages` stages."""
    c = config or GAConfig()
    f = move_scale(n_stages)
    return dataclasses.replace(c, sigma_heading_deg=c.sigma_heading_deg * f,
                               jitter_heading_deg=c.jitter_heading_deg * f,
                               init_spread_heading_deg=c.init_spread_heading_deg * f)
