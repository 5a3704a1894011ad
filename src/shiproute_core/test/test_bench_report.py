"""Benchmark figures: one parsable JSON line with --json, aligned text lines otherwise."""

from __future__ import annotations

import json

import pytest
from shiproute_core.bench_report import print_figures


def test_json_is_one_line_with_every_figure(capsys: pytest.CaptureFixture[str]) -> None:
    figures = {"plans": 53, "planner_rss_mb_peak": 612.5, "per_lane": [{"lane": "a"}]}
    print_figures(figures, as_json=True, leave_out=("per_lane",))
    lines = capsys.readouterr().out.splitlines()
    assert len(lines) == 1 and json.loads(lines[0]) == figures


def test_text_aligns_names_and_leaves_out_long_figures(
        capsys: pytest.CaptureFixture[str]) -> None:
    print_figures({"plans": 53, "planner_rss_mb_peak": 612.5, "per_lane": [1, 2]},
                  as_json=False, leave_out=("per_lane",))
    assert capsys.readouterr().out.splitlines() == [
        "              plans: 53", "planner_rss_mb_peak: 612.5"]
