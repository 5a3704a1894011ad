"""Objectives fuel, distance, eta, co2 and cost: figures with their sources, and each one
moving the plan the way it should against the fuel objective."""

from __future__ import annotations

from pathlib import Path

import pytest
from shiproute_planner.errors import InvalidVoyageError
from shiproute_planner.objectives import (
    DEFAULT_CHARTER_USD_PER_DAY,
    DEFAULT_FUEL_PRICE_USD_PER_T,
    Economics,
    objective_terms,
)
from shiproute_planner.plan_request import build_request, run_request
from shiproute_planner.ship import ShipFileError, load_ship
from shiproute_planner.ship.loading import ship_file_path

# 5 days for ~1,560 NM: about 13 kn needed, the ship makes ~24 kn: a flexible arrival
FLEX = dict(origin="35,160", destination="38,190", depart="2026-03-10T00:00Z", rta="5d",
            budget="1500ev")


def test_co2_factors_are_the_imo_ones() -> None:
    # IMO MEPC.308(73) para 2.2: Cf [t CO2 / t fuel]
    for fuel, cf in (("HFO", 3.114), ("LFO", 3.151), ("MDO", 3.206), ("MGO", 3.206),
                     ("LNG", 2.750)):
        t = objective_terms("co2", {}, Economics(fuel_type=fuel))
        assert t.per_t_fuel == cf and t.per_h == 0.0
    t = objective_terms("co2", {})
    assert t.per_t_fuel == 3.114 and "default HFO" in t.notes[0]


def test_cost_prices_from_cli_then_ship_file_then_defaults() -> None:
    t = objective_terms("cost", {})
    assert t.per_t_fuel == DEFAULT_FUEL_PRICE_USD_PER_T
    assert t.per_h == DEFAULT_CHARTER_USD_PER_DAY / 24 and len(t.notes) == 3
    t = objective_terms("cost", {"fuel_price_usd_per_t": 700.0, "charter_usd_per_day": 48000.0})
    assert (t.per_t_fuel, t.per_h) == (700.0, 2000.0)
    t = objective_terms("cost", {"fuel_price_usd_per_t": 700.0}, Economics(None, 450.0, 24000))
    assert (t.per_t_fuel, t.per_h) == (450.0, 1000.0)
    with pytest.raises(InvalidVoyageError, match="fuel type 'coal'"):
        Economics(fuel_type="coal")
    with pytest.raises(InvalidVoyageError, match="charter_usd_per_day"):
        Economics(charter_usd_per_day=-5.0)


def test_ship_file_fuel_type_and_economics(tmp_path: Path) -> None:
    text = "\n".join(line for line in ship_file_path("container_4600teu").read_text().splitlines()
                     if not line.startswith("fuel_type:"))
    f = tmp_path / "ship.yaml"
    f.write_text(text + "\nfuel_type: lng\neconomics:\n  charter_usd_per_day: 30000\n")
    assert dict(load_ship(f).economics) == {"fuel_type": "LNG", "charter_usd_per_day": 30000.0}
    f.write_text(text + "\nfuel_type: coal\n")
    with pytest.raises(ShipFileError, match="fuel_type"):
        load_ship(f)


@pytest.fixture(scope="module")
def fuel_plan():
    return run_request(build_request(**FLEX))


def test_eta_and_expensive_time_arrive_earlier_than_fuel(fuel_plan) -> None:
    eta = run_request(build_request(**FLEX, objective="eta"))
    cost = run_request(build_request(**FLEX, objective="cost", fuel_price_usd_per_t=600.0,
                                     charter_usd_per_day=400_000.0))
    cheap_time = run_request(build_request(**FLEX, objective="cost", fuel_price_usd_per_t=600.0,
                                           charter_usd_per_day=0.0))
    assert fuel_plan.feasible and eta.feasible and cost.feasible
    # fuel rises ~ with speed squared per mile: the least-fuel plan uses the time it has
    assert fuel_plan.eta_s > fuel_plan.rta_s - 6 * 3600
    assert eta.eta_s < fuel_plan.eta_s - 24 * 3600
    assert cost.eta_s < fuel_plan.eta_s - 12 * 3600 and cost.total_fuel_t > fuel_plan.total_fuel_t
    # with time free, cost is fuel x price: the least-fuel plan's arrival and fuel
    assert cheap_time.total_fuel_t == pytest.approx(fuel_plan.total_fuel_t, rel=0.02)
    goal = cost.extra["objective"]
    assert goal["value"] == pytest.approx(
        600.0 * cost.total_fuel_t + 400_000.0 * cost.total_time_s / 86400.0, rel=1e-9)


def test_co2_is_fuel_times_the_factor_and_picks_the_least_fuel_route(fuel_plan) -> None:
    co2 = run_request(build_request(**FLEX, objective="co2", fuel_type="MGO"))
    # a constant factor does not change which route is best: same search, same plan
    assert co2.total_fuel_t == pytest.approx(fuel_plan.total_fuel_t, rel=0.01)
    assert co2.extra["objective"]["value"] == pytest.approx(3.206 * co2.total_fuel_t)


@pytest.mark.slow
def test_distance_objective_sails_a_shorter_route_in_a_storm() -> None:
    storm = dict(origin="Busan", destination="Long Beach", depart="2026-03-03T18:00Z",
                 rta="13d", budget="3000ev")
    from shiproute_planner.plan_setup import load_forecast

    fc = load_forecast("storm_march")
    fuel = run_request(build_request(**storm), fc)
    dist = run_request(build_request(**storm, objective="distance"), fc)
    assert dist.total_distance_nm < fuel.total_distance_nm
    # never shorter than the great circle between the ports (5,219 NM Busan - Long Beach,
    # WGS 84 geodesic between the port positions 35.08 N 129.11 E and 33.74 N 118.22 W)
    assert dist.total_distance_nm > 5200
