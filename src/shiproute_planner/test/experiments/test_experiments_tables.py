"""Tables 11/12 and 15 layouts: percentages against the first row / the best known optimum."""

from __future__ import annotations

import numpy as np
from shiproute_planner.experiments.outcome import (
    MethodOutcome,
    RepeatRow,
    comparison_table,
    repeat_table,
)


def _row(method: str, tfoc: float, dist: float, varied: bool) -> MethodOutcome:
    z = np.zeros(2)
    return MethodOutcome(method, method, tfoc, dist, 1000.0, 1000.0, 0, True, (), varied, 77.0,
                         1.5, 10, z, z, z[:1] + 77.0, z[:1] + 17.0, z[:1])


def test_comparison_table_percent_of_first_row() -> None:
    text = comparison_table([_row("isochrone", 684.8, 5248, False),
                             _row("seed_ga", 629.4, 5223, True)])
    # the reference study's table 11: 629.4 t is 91.9 % of 684.8 t, 5,223 NM is 99.5 %
    assert " 91.9%" in text and " 99.5%" in text and "varied" in text and "77.0" in text


def test_repeat_table_mean_std_against_best_known() -> None:
    # table 15, SPEA2 row: 685 683 676 695 670 -> mean 681.8, sample std 9.5 (629.4 t optimum)
    row = RepeatRow("spea2", "SPEA2", (685.0, 683.0, 676.0, 695.0, 670.0), (True,) * 5, 100, 1.0)
    assert abs(row.mean_tfoc_t - 681.8) < 1e-9
    assert round(row.std_tfoc_t, 1) == 9.5  # 9.47, printed as 9.5 in the study
    text = repeat_table([row], 629.4)
    assert "681.8" in text and "108.3%" in text and "9.5" in text
    assert row.as_json(629.4)["mean_pct_of_best_known"] == 108.33
