"""Warm re-plan from a previous plan shifted to the ship's position (planner node path)."""

from __future__ import annotations

import dataclasses
from datetime import timedelta

import numpy as np
from shiproute_planner.planning import plan_voyage
from shiproute_planner.route.seeding import sane_rpm

JUNE = "2026-06-01T00:00Z"


def test_sane_rpm_fills_gaps_from_neighbours_and_clips():
    r = sane_rpm(np.array([np.nan, 70.0, np.nan, np.nan, 90.0, 200.0, np.nan]), 30.0, 104.0)
    assert np.all(np.isfinite(r))
    assert r[0] == 70.0 and r[1] == 70.0 and r[4] == 90.0 and r[5] == 104.0 and r[6] == 104.0
    assert r[2] == 70.0 and r[3] == 90.0  # nearest finite neighbour
    assert np.all(sane_rpm(np.full(3, np.nan), 30.0, 104.0) == 67.0)


def test_warm_replan_survives_nan_rpm_in_previous_plan(land_mask):
    # regression: "planning failed: input 'rpm': value at flat index 0 is NaN or outside the
    # valid range" on a warm re-plan; the previous plan's RPMs seed the GA, so a NaN there
    # (or an out-of-range value from another ship) reached the ship model unchecked
    first = plan_voyage("New York", "Lisbon", JUNE, timedelta(days=8), "container_4600teu",
                        None, budget_s=60.0, max_generations=2, land=land_mask)
    lon, lat, t = first.track()
    k = len(t) // 3
    bad = tuple(dataclasses.replace(w, shaft_rpm=float("nan")) if i in (k, k + 1, k + 2)
                else w for i, w in enumerate(first.waypoints))
    previous = dataclasses.replace(first, waypoints=bad)
    assert np.isnan(previous.leg_rpm()).any()
    again = plan_voyage("New York", "Lisbon", JUNE, timedelta(days=8), "container_4600teu",
                        None, previous_plan=previous, position=(lat[k], lon[k], t[k] + 600.0),
                        budget_s=60.0, max_generations=2, land=land_mask)
    rpm = again.leg_rpm()
    assert np.all(np.isfinite(rpm)) and rpm.min() >= 30.0
    assert again.departure_s == t[k] + 600.0
