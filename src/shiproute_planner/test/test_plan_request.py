"""The shared request builder behind `shiproute plan` and `shiproute fleet`: budgets, times,
and a plan at an evaluation budget that is the same plan every time (same seed)."""

from __future__ import annotations

import json
import math

import pytest
from shiproute_planner.errors import InvalidVoyageError
from shiproute_planner.plan_request import Budget, build_request


def test_budget_and_time_parsing():
    assert Budget.parse("3s") == Budget(3.0, 0)
    assert Budget.parse("2m") == Budget(120.0, 0)
    assert Budget.parse("4000ev") == Budget(math.inf, 4000)
    assert Budget.parse("250 evals") == Budget(math.inf, 250)
    for bad in ("fast", "0s", "0ev", "-3"):
        with pytest.raises(InvalidVoyageError, match=r"budget|duration"):
            Budget.parse(bad)
    req = build_request(origin="Busan", destination="Yokohama", depart="2026-03-04T00:00Z",
                        rta="3d", via=["Kobe@2026-03-05T12:00Z"])
    assert req.rta_s - req.depart_s == 3 * 86400.0
    assert req.via == ("Kobe",) and req.via_rta_s[0] == req.depart_s + 36 * 3600.0
    with pytest.raises(InvalidVoyageError, match="RTA must be after"):
        build_request(origin="A", destination="B", depart="2026-03-04T00:00Z",
                      rta="2026-03-03T00:00Z")
    with pytest.raises(InvalidVoyageError, match="departure 'soon'"):
        build_request(origin="A", destination="B", depart="soon", rta="3d")
    with pytest.raises(InvalidVoyageError, match="ship model"):
        build_request(origin="A", destination="B", depart="2026-03-04T00:00Z", rta="3d",
                      model="magic")


def test_plan_cli_evaluation_budget_is_reproducible(tmp_path, capsys):
    from shiproute_planner.cli.plan import main

    fuels = []
    for k in range(2):
        out = tmp_path / str(k)
        code = main(["--from", "Shanghai", "--to", "Busan", "--depart", "2026-03-04T00:00Z",
                     "--rta", "2d", "--budget", "400ev", "--seed", "5", "--out", str(out),
                     "--name", "p", "--no-plot"])
        assert code in (0, 1)
        data = json.loads((out / "p.json").read_text())
        assert data["evaluations"] == 400  # the budget is exact
        fuels.append(data["total_fuel_t"])
    assert fuels[0] == fuels[1]
    capsys.readouterr()
    assert main(["--from", "Shanghai", "--to", "Busan", "--depart", "tomorrow", "--rta", "2d",
                 "--out", str(tmp_path)]) == 2
    assert "departure 'tomorrow'" in capsys.readouterr().err
