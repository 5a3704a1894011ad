"""The CLI's numeric options are held to the node parameters' ranges (one table): a value
outside them exits 2 with a message naming the option and its valid range, no traceback."""

from __future__ import annotations

import math
import os
import subprocess
import sys

import pytest
from shiproute_planner.checks.parameters import RANGES
from shiproute_planner.cli import check as check_cli
from shiproute_planner.cli import plan as plan_cli
from shiproute_planner.cli.option_ranges import PLAN_OPTIONS, budget_number, check_options
from shiproute_planner.errors import ParameterError, PlannerError
from shiproute_planner.plan_request import build_request
from shiproute_planner.voyage_params import check_parameter

VOYAGE = ["--from", "Busan", "--to", "Long Beach", "--depart", "2026-03-03T18:00Z",
          "--rta", "13d", "--no-plot"]

# (option, value as typed, parameter whose range it must name)
BAD = [
    ("--stage-hours", "0", "stage_hours"),
    ("--stage-hours", "1000", "stage_hours"),
    ("--stage-hours", "nan", "stage_hours"),
    ("--budget", "-1s", "budget_s"),
    ("--budget", "0", "budget_s"),
    ("--budget", "2h", "budget_s"),
    ("--budget", "100000000ev", "budget_evaluations"),
    ("--ukc-margin", "1e6", "ukc_margin_m"),
    ("--ukc-margin", "-0.5", "ukc_margin_m"),
    ("--clearance-nm", "inf", "clearance_nm"),
    ("--clearance-nm", "-1", "clearance_nm"),
    ("--open-sea-clearance-nm", "5.5", "open_sea_clearance_nm"),
    ("--open-sea-clearance-nm", "-0.1", "open_sea_clearance_nm"),
    ("--approach-clearance-nm", "3.5", "approach_clearance_nm"),
    ("--approach-clearance-nm", "nan", "approach_clearance_nm"),
    ("--approach-zone-nm", "250", "approach_zone_nm"),
    ("--seed", "-1", "rng_seed"),
    ("--persistence-hours", "-5", "persistence_hours"),
    ("--persistence-hours", "100000", "persistence_hours"),
]


def _range_text(parameter: str) -> str:
    rule = RANGES[parameter]
    return f"{rule.lowest:g}..{rule.highest:g}"


@pytest.mark.parametrize(("option", "value", "parameter"), BAD)
def test_plan_option_outside_range_exits_2_naming_it(option, value, parameter, capsys, tmp_path):
    code = plan_cli.main([*VOYAGE, "--out", str(tmp_path), f"{option}={value}"])
    err = capsys.readouterr().err
    assert code == 2
    assert option in err and _range_text(parameter) in err, err
    assert RANGES[parameter].why.split(";")[0] in err  # the reason for the bounds
    assert "Traceback" not in err
    assert not list(tmp_path.iterdir())  # refused before anything was planned or written


def test_every_option_maps_to_a_node_parameter_range():
    for option, (_dest, parameter) in PLAN_OPTIONS.items():
        assert parameter in RANGES, option
    # the node refuses the same values through the same table
    for parameter, value in (("stage_hours", 1000.0), ("ukc_margin_m", 1e6),
                             ("clearance_nm", math.inf), ("ukc_margin_m", -0.5)):
        reason = check_parameter(parameter, value)
        assert reason is not None and _range_text(parameter) in reason


@pytest.mark.parametrize("parameter", ["stage_hours", "ukc_margin_m", "clearance_nm",
                                       "persistence_hours", "open_sea_clearance_nm",
                                       "approach_clearance_nm", "approach_zone_nm"])
def test_range_edges_are_accepted_and_just_outside_refused(parameter):
    rule = RANGES[parameter]
    option = next(o for o, (_d, p) in PLAN_OPTIONS.items() if p == parameter)
    args = plan_cli.build_parser().parse_args(VOYAGE)
    for edge in (rule.lowest, rule.highest):
        setattr(args, PLAN_OPTIONS[option][0], edge)
        check_options(args, PLAN_OPTIONS, budget_option="--budget")
    for outside in (rule.lowest - 1e-6, rule.highest * (1 + 1e-6) + 1e-6):
        setattr(args, PLAN_OPTIONS[option][0], outside)
        with pytest.raises(ParameterError, match=option):
            check_options(args, PLAN_OPTIONS, budget_option="--budget")


def test_defaults_pass_and_budget_kinds_map_to_their_ranges():
    check_options(plan_cli.build_parser().parse_args(VOYAGE), PLAN_OPTIONS,
                  budget_option="--budget")
    assert budget_number("4000ev") == ("budget_evaluations", 4000)
    assert budget_number("90m") == ("budget_s", 5400.0)
    assert budget_number("-3") == ("budget_s", -3.0)
    assert budget_number("-2m") == ("budget_s", -120.0)
    with pytest.raises(PlannerError, match="at least 1 evaluation"):
        budget_number("0ev")
    with pytest.raises(PlannerError, match="--budget: duration 'fast': use a number"):
        budget_number("fast")


def test_fleet_requests_use_the_same_table():
    """`build_request` (shared by plan and fleet) refuses what the node refuses."""
    common = dict(origin="Busan", destination="Long Beach", depart="2026-03-03T18:00Z",
                  rta="13d")
    with pytest.raises(ParameterError, match=r"stage_hours = 1000.0 is outside 0\.1\.\.24"):
        build_request(**common, stage_hours=1000.0)
    with pytest.raises(ParameterError, match="budget_s"):
        build_request(**common, budget="0.001s")
    with pytest.raises(ParameterError, match="rng_seed"):
        build_request(**common, seed=-4)
    assert build_request(**common, stage_hours=24.0, budget="100ev").stage_hours == 24.0


def test_check_cli_refuses_out_of_range_margins(capsys, tmp_path):
    route = tmp_path / "r.geojson"
    route.write_text('{"type": "FeatureCollection", "features": []}')
    assert check_cli.main([str(route), "--ukc-margin", "500"]) == 2
    err = capsys.readouterr().err
    assert "--ukc-margin" in err and _range_text("ukc_margin_m") in err


def test_installed_command_exits_2_without_traceback():
    exe = os.path.join(os.path.dirname(sys.executable), "shiproute")
    if not os.path.exists(exe):
        pytest.skip("the shiproute console script is not installed in this interpreter's venv")
    run = subprocess.run([exe, "plan", *VOYAGE, "--stage-hours", "0"], capture_output=True,
                         text=True, timeout=120)
    assert run.returncode == 2
    assert "--stage-hours" in run.stderr and "1..24 h" in run.stderr
    assert "Traceback" not in run.stderr
