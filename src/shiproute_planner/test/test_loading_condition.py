"""The loading condition chosen by name or drafts (CLI, request, node parameter) changes the
ship the planner sails: displacement, resistance, fuel, draft for the under-keel clearance."""

from __future__ import annotations

import pytest
from shiproute_planner.errors import InvalidVoyageError
from shiproute_planner.plan_request import build_request, run_request
from shiproute_planner.ship import load_ship
from shiproute_planner.ship.condition import ship_in_condition
from shiproute_planner.voyage_ship import loaded_ship, model_choice_reason

OCEAN = dict(origin="35,160", destination="38,190", depart="2026-03-10T00:00Z", rta="4d",
             budget="600ev")


def test_named_conditions_and_drafts() -> None:
    design, ballast = load_ship("container_4600teu"), load_ship("container_4600teu", "ballast")
    assert ship_in_condition("container_4600teu", "ballast") == ballast
    same = ship_in_condition("container_4600teu", "12.0,12.0")
    assert same.condition.displacement_t == design.condition.displacement_t
    deeper = ship_in_condition("container_4600teu", "12.5,12.5")
    # parallel sinkage: + rho Cwp L B dT = 1.025 x 0.76 x 246 x 37.5 x 0.5 = 3,593 t
    assert deeper.condition.displacement_t - design.condition.displacement_t == pytest.approx(
        1.025 * 0.76 * 246.0 * 37.5 * 0.5, rel=1e-9)
    light = ship_in_condition("container_4600teu", "8.0,9.0")  # nearest named: ballast
    assert light.condition.name.startswith("ballast") and light.condition.gm_m == 3.5


@pytest.mark.parametrize("bad, why", [("25,25", "below the hull depth"),
                                      ("0.2,9", "0.5 m or more"),
                                      ("6,14", "trim"),
                                      ("laden", "no condition 'laden'"),
                                      ("12;12", "drafts fore,aft")])
def test_bad_loading_is_refused_with_the_reason(bad: str, why: str) -> None:
    with pytest.raises(InvalidVoyageError, match=why):
        loaded_ship("container_4600teu", bad)
    assert why in (model_choice_reason("container_4600teu", "", bad) or "")


def test_ballast_burns_less_than_design_on_the_same_voyage() -> None:
    design = run_request(build_request(**OCEAN))
    ballast = run_request(build_request(**OCEAN, loading="ballast"))
    drafts = run_request(build_request(**OCEAN, loading="7.5,9.5"))
    assert design.feasible and ballast.feasible
    assert ballast.extra["loading"]["condition"] == "ballast"
    assert design.extra["loading"]["draft_aft_m"] == 12.0
    # 45,300 t against 70,300 t: less wetted surface and displacement, less resistance
    # (the ship file's Holtrop-Mennen model gives 2-7 % less power at 14-18 kn in ballast,
    # its trim and emerging bulb taking back part of what the lighter hull saves)
    assert ballast.total_fuel_t < 0.995 * design.total_fuel_t
    assert drafts.total_fuel_t == pytest.approx(ballast.total_fuel_t, rel=0.01)


def test_cli_loading_error_exits_2(capsys) -> None:
    from shiproute_planner.cli.plan import main

    rc = main(["--from", "35,160", "--to", "38,190", "--depart", "2026-03-10T00:00Z",
               "--rta", "4d", "--loading", "25,25", "--no-plot"])
    err = capsys.readouterr().err
    assert rc == 2 and "hull depth" in err and "Traceback" not in err
