"""Outputs: RTZ 1.2 valid against the IEC 61174 schema, GeoJSON and JSON summary content."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET
from datetime import timedelta

import pytest
from shiproute_planner.errors import OutputError
from shiproute_planner.io.rtz import NS, validate_rtz, write_rtz
from shiproute_planner.io.summary import plan_geojson, write_json
from shiproute_planner.planning import plan_voyage


@pytest.fixture(scope="module")
def plan(land_mask):
    return plan_voyage("New York", "Lisbon", "2026-06-01T00:00Z", timedelta(days=8),
                       "container_4600teu", None, budget_s=120.0, max_generations=2,
                       land=land_mask)


def test_rtz_is_valid_rtz_1_2(plan, tmp_path):
    path = write_rtz(plan, tmp_path / "ny_lisbon.rtz")
    validate_rtz(path)
    root = ET.parse(path).getroot()
    assert root.get("version") == "1.2"
    info = root.find(f"{{{NS}}}routeInfo")
    assert info.get("routeName") == "ny_lisbon"
    assert "seed_ga" in info.get("optimizationMethod")
    assert float(info.get("vesselMaxWave")) > 0 and float(info.get("vesselMaxWind")) > 0
    wps = root.findall(f".//{{{NS}}}waypoint")
    ids = [int(w.get("id")) for w in wps]
    assert ids == list(range(1, len(plan.waypoints) + 1))
    sched = root.findall(f".//{{{NS}}}scheduleElement")
    assert [int(s.get("waypointId")) for s in sched] == ids
    assert all(s.get("rpm") and s.get("fuel") and s.get("speed") for s in sched[:-1])
    assert sched[-1].get("eta") is not None


def test_rtz_name_mismatch_is_rejected(plan, tmp_path):
    path = write_rtz(plan, tmp_path / "a.rtz")
    renamed = path.rename(tmp_path / "b.rtz")
    with pytest.raises(OutputError, match="routeName"):
        validate_rtz(renamed)


def test_geojson_and_summary(plan, tmp_path):
    gj = plan_geojson(plan)
    lines = [f for f in gj["features"] if f["geometry"]["type"] == "LineString"]
    assert len(lines) == len(plan.waypoints) - 1
    assert {"shaft_rpm", "leg_fuel_t", "hs_m", "constraint_flags"} <= set(lines[0]["properties"])
    data = json.loads(write_json(plan, tmp_path / "s.json").read_text())
    assert data["total_fuel_t"] == pytest.approx(sum(leg["leg_fuel_t"] for leg in data["legs"]))
    assert data["baseline"]["fuel_t"] == pytest.approx(plan.baseline_fuel_t)
    assert len(data["legs"]) == len(plan.waypoints) - 1
    # where the compute time went: the phases are parts of the plan's total, the search one
    timing = data["timing_s"]
    phases = {k: v for k, v in timing.items() if k not in ("budget", "total")}
    assert timing["budget"] == 120.0 and phases["search"] > 0.0
    assert sum(phases.values()) <= timing["total"] + 0.001 * len(phases)


def test_cli_writes_all_outputs(tmp_path, capsys):
    from shiproute_planner.cli.plan import main

    code = main(["--from", "New York", "--to", "Lisbon", "--depart", "2026-06-01T00:00Z",
                 "--rta", "8d", "--budget", "1s", "--out", str(tmp_path), "--name", "ny"])
    assert code in (0, 1)  # 1 = plan infeasible within the tiny budget, still written
    out = capsys.readouterr().out
    assert "fuel" in out and "baseline" in out and "ETA" in out
    for ext in ("rtz", "geojson", "json", "png"):
        assert (tmp_path / f"ny.{ext}").stat().st_size > 0
    validate_rtz(tmp_path / "ny.rtz")
