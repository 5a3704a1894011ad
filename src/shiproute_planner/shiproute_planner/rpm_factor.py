"""The RPM factor that fits legs into a time window (speed ~ RPM, so leg times scale as
1 / RPM): shared by the re-timing of a re-plan's route (`replan_retime`) and the re-timed
repairs of a stale re-plan's seeds (`track_repairs`)."""

from __future__ import annotations

import numpy as np

TARGET_BEFORE_RTA_S = 1800.0  # re-timed routes and repairs aim this long before the RTA


def retimed_rpm(rpm: np.ndarray, duration_s: np.ndarray, cut: int, window_s: float,
                factor_before: float = 1.0) -> np.ndarray | None:
    """`rpm` per leg with the legs before `cut` scaled by `factor_before` and the legs from
    `cut` on by the factor that makes them take what is left of `window_s` (leg times scale
    as 1 / RPM: speed ~ RPM); None when nothing is left of the window."""
    before_s = float(np.sum(duration_s[:cut]))
    after_s = float(np.sum(duration_s[cut:]))
    left_s = window_s - before_s / factor_before
    if left_s <= 0.0 or after_s <= 0.0:
        return None
    out = np.asarray(rpm, dtype=float).copy()
    out[:cut] *= factor_before
    out[cut:] *= after_s / left_s
    return out
