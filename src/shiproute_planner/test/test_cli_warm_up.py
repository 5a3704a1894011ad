"""A one-shot `shiproute plan` process must give the search its budget: its one-off set-up
(compiled kernels, land and depth maps, sea lanes, coastal passages) is done before the
budget's clock, as the planner node does at start. Counted inside the budget it left an
ocean crossing 0 generations of a 3-s budget (the plan was the best seed track)."""

from __future__ import annotations

import json

from shiproute_planner.cli.plan import main as plan_main


def test_cli_plan_warms_up_outside_the_budget_and_searches(tmp_path, capsys):
    code = plan_main(["--from", "Busan", "--to", "Long Beach", "--depart",
                      "2026-03-03T18:00Z", "--rta", "13d", "--out", str(tmp_path),
                      "--no-plot", "--budget", "3s"])
    assert code in (0, 1)
    err = capsys.readouterr().err
    assert "warm-up:" in err and "before the budget's clock" in err
    (path,) = tmp_path.glob("*.json")
    doc = json.loads(path.read_text())
    # a GA generation is one population (~100 routes): an ocean crossing that kept its
    # budget for the search makes many; the best seed alone is generation 0
    assert doc["generations"] >= 5, doc["generations"]
