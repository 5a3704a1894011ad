"""The time-fuel front: monotone (more time, less fuel), feasible at both ends, from the
earliest safe arrival to the latest arrival, written as JSON / GeoJSON / PNG / RTZ."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from shiproute_planner.front import pareto, plan_front
from shiproute_planner.plan_request import build_request, run_request

FLEX = dict(origin="35,160", destination="38,190", depart="2026-03-10T00:00Z", rta="5d")


@pytest.fixture(scope="module")
def front():
    req = build_request(**FLEX, objective="front", budget="4000ev", front_points=5)
    return plan_front(req)


def test_front_is_monotone_with_feasible_ends(front) -> None:
    plans = front.plans
    assert len(plans) >= 4 and front.monotone
    assert plans[0].feasible and plans[-1].feasible
    assert all(p.feasible or p.infeasible_reasons for p in plans)  # feasible or flagged
    # the slow end meets the latest arrival and uses most of the time it has
    assert plans[-1].eta_s <= front.latest_arrival_s + 60.0
    assert plans[-1].eta_s > front.latest_arrival_s - 6 * 3600.0
    # the fast end is the earliest arrival: no faster than the engine's top calm speed
    # allows (~1,560 NM at <= 25 kn takes >= 62 h), and well ahead of the slow end
    hours = (plans[0].eta_s - plans[0].departure_s) / 3600.0
    assert plans[0].total_distance_nm / hours < 25.0
    assert plans[-1].eta_s - plans[0].eta_s > 24 * 3600.0
    # fuel per NM grows with speed: the fastest plan burns far more than the slowest
    assert plans[0].total_fuel_t > 1.5 * plans[-1].total_fuel_t


def test_front_ends_match_single_plans(front) -> None:
    slow = run_request(build_request(**FLEX, budget="1500ev"))
    assert front.plans[-1].total_fuel_t == pytest.approx(slow.total_fuel_t, rel=0.03)


def test_pareto_drops_dominated_plans(front) -> None:
    a, b = front.plans[0], front.plans[-1]
    keep, dropped = pareto([b, a, a])
    assert keep == [a, b] and dropped == [a]


def test_cli_front_writes_json_geojson_png_rtz(tmp_path: Path, capsys) -> None:
    from shiproute_planner.cli.plan import main

    rc = main(["--from", "35,160", "--to", "38,190", "--depart", "2026-03-10T00:00Z",
               "--rta", "5d", "--objective", "front", "--front-points", "3",
               "--budget", "1500ev", "--out", str(tmp_path), "--name", "f"])
    out = capsys.readouterr().out
    assert rc == 0, out
    data = json.loads((tmp_path / "f.json").read_text())
    assert len(data["points"]) == 3 and data["monotone"]
    hours = [p["voyage_h"] for p in data["points"]]
    fuel = [p["fuel_t"] for p in data["points"]]
    assert hours == sorted(hours) and fuel == sorted(fuel, reverse=True)
    gj = json.loads((tmp_path / "f.geojson").read_text())
    assert {f["properties"]["front_point"] for f in gj["features"]} == {0, 1, 2}
    assert (tmp_path / "f.png").stat().st_size > 10_000
    assert all((tmp_path / f"f_{k}.rtz").is_file() for k in range(3))
    assert "time-fuel front" in out


def test_front_refuses_bad_point_counts(capsys) -> None:
    from shiproute_planner.cli.plan import main

    rc = main(["--from", "35,160", "--to", "38,190", "--depart", "2026-03-10T00:00Z",
               "--rta", "5d", "--objective", "front", "--front-points", "1", "--no-plot"])
    assert rc == 2 and "front points" in capsys.readouterr().err
