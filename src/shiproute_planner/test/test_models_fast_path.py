"""Every ship model plans through the GA's compiled fast path (tabulated into the fast
tables), and the plan's fuel agrees with the model itself evaluated on the plan's legs."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from shiproute_planner.errors import InvalidVoyageError
from shiproute_planner.learned.select import resolve_model
from shiproute_planner.plan_request import build_request, run_request
from shiproute_planner.plan_setup import chosen_model as _chosen_model
from shiproute_planner.route.environment import Environment
from shiproute_planner.ship import (
    FastModel,
    KwonModel,
    PhysicsModel,
    ProfileGrid,
    ProfileModel,
    export_profile,
    load_ship,
)
from shiproute_planner.ship.seastate import SeaState
from test_ship_model_choice import _zero_model

OCEAN = dict(origin="35,160", destination="38,190", depart="2026-03-10T00:00Z", rta="4d",
             budget="600ev")


@pytest.fixture(scope="module")
def profile_file(tmp_path_factory) -> Path:
    """A NetCDF performance profile of the 4,600 TEU ship exported from its physics model."""
    ship = load_ship("container_4600teu")
    path = tmp_path_factory.mktemp("profile") / "container_4600teu.nc"
    export_profile(PhysicsModel(ship), path, ProfileGrid.for_ship(ship))
    return path


def direct_fuel_t(plan, model, env: Environment) -> float:
    """Fuel of the plan's legs by `model` itself: its fuel rate at each leg's RPM, heading
    and the sea state at the leg's start, times the leg's duration."""
    wps = plan.waypoints[:-1]
    lon = np.array([w.lon_deg for w in wps])
    lat = np.array([w.lat_deg for w in wps])
    t = np.array([w.time_s for w in wps])
    sea = env.sea_state(lon, lat, t)
    rpm = np.array([w.shaft_rpm for w in wps])
    hdg = np.array([w.heading_deg for w in wps])
    dur_h = np.array([w.leg_duration_s for w in wps]) / 3600.0
    return float(np.sum(model.evaluate(rpm, hdg, sea).fuel_t_per_h * dur_h))


@pytest.mark.parametrize("choice", ["physics", "kwon", "profile", "learned"])
def test_each_model_plans_on_the_fast_path_within_1pct_of_itself(
        choice: str, profile_file: Path, tmp_path: Path) -> None:
    ship = load_ship("container_4600teu")
    model_arg = {"profile": f"profile:{profile_file}",
                 "learned": f"learned:{_zero_model(ship, tmp_path / 'z.nc')}"}.get(choice, choice)
    fm, _ = resolve_model(ship, model_arg)
    assert isinstance(fm, FastModel)  # the GA's compiled evaluator takes it
    direct = {"physics": PhysicsModel(ship), "kwon": KwonModel(ship),
              "profile": ProfileModel(ship, profile_file)}.get(choice, PhysicsModel(ship))
    plan = run_request(build_request(**OCEAN, model=model_arg))
    assert plan.feasible, plan.infeasible_reasons
    ref = direct_fuel_t(plan, direct, Environment(direct))
    assert plan.total_fuel_t == pytest.approx(ref, rel=0.01), (choice, plan.total_fuel_t, ref)
    if choice != "physics":
        assert any("tabulated" in w or "learned" in w for w in plan.warnings)


def test_kwon_tables_follow_kwon_in_calm_water_and_its_speed_loss_in_weather() -> None:
    ship = load_ship("container_4600teu")
    fm, notes = resolve_model(ship, "kwon")
    kwon = KwonModel(ship)
    rpm = np.linspace(ship.engine.rpm_min, ship.engine.rpm_max, 40)
    a, b = fm.evaluate(rpm, 0.0, SeaState.calm(40)), kwon.evaluate(rpm, 0.0, SeaState.calm(40))
    np.testing.assert_allclose(a.stw_m_s, b.stw_m_s, rtol=5e-3)
    np.testing.assert_allclose(a.fuel_t_per_h, b.fuel_t_per_h, rtol=5e-3)
    # Beaufort 8 head wind and sea: Kwon's loss for a 0.6-Cb container ship at ~18 kn is
    # several per cent; the tables must slow the ship too, by a similar amount
    sea = SeaState.from_arrays(wind_u_m_s=0.0, wind_v_m_s=-19.0, wind_wave_hs_m=5.5,
                               wind_wave_from_deg=0.0, wind_wave_period_s=9.0)
    v_k = kwon.evaluate(np.array([77.0]), 0.0, sea).stw_m_s[0]
    v_t = fm.evaluate(np.array([77.0]), 0.0, sea).stw_m_s[0]
    v_calm = kwon.evaluate(np.array([77.0]), 0.0, SeaState.calm(1)).stw_m_s[0]
    assert v_k < v_calm and v_t < v_calm
    assert abs((v_calm - v_t) / (v_calm - v_k) - 1.0) < 0.5
    assert "tabulated for the fast path" in notes[1]
    # Kwon's premise: the engine holds its calm-water output, so the fuel rate at an RPM is
    # the calm-water one in any weather; the tables must not burn the loaded propeller's torque
    f_calm = kwon.evaluate(np.array([77.0]), 0.0, SeaState.calm(1)).fuel_t_per_h[0]
    assert kwon.evaluate(np.array([77.0]), 0.0, sea).fuel_t_per_h[0] == pytest.approx(f_calm)
    assert fm.evaluate(np.array([77.0]), 0.0, sea).fuel_t_per_h[0] == pytest.approx(f_calm,
                                                                                   rel=1e-3)


def test_profile_of_another_ship_is_refused(profile_file: Path) -> None:
    with pytest.raises(InvalidVoyageError, match="profile of ship 'container_4600teu', not of "
                                                 "'vlcc_270k'"):
        _chosen_model("vlcc_270k", f"profile:{profile_file}")


def test_cli_model_of_another_ship_exits_2(profile_file: Path, capsys) -> None:
    from shiproute_planner.cli.plan import main

    rc = main(["--from", "35,160", "--to", "38,190", "--depart", "2026-03-10T00:00Z",
               "--rta", "4d", "--ship", "vlcc_270k", "--model", f"profile:{profile_file}",
               "--no-plot"])
    err = capsys.readouterr().err
    assert rc == 2 and "another ship" in err and "Traceback" not in err


@pytest.mark.slow
def test_kwon_in_the_storm_agrees_with_kwon_itself_within_1pct() -> None:
    """The bundled storm voyage: the tables fit Kwon's weather loss only approximately (the
    plan states median and 90th-percentile gaps), yet over the planned voyage the fuel of the
    fast path and of Kwon's model on the same legs agree within 1 %: Kwon's engine keeps its
    calm-water output in weather, and the tables burn none of the extra propeller torque
    (fitted power share 0), so the gap left is table interpolation."""
    from shiproute_planner.plan_setup import load_forecast
    from shiproute_weather.sampling.sampler import ForecastSampler

    fc = ForecastSampler(load_forecast("storm_march"))
    kwon = KwonModel(load_ship("container_4600teu"))
    plan = run_request(build_request(origin="Busan", destination="Long Beach",
                                     depart="2026-03-03T18:00Z", rta="13d", budget="3000ev",
                                     model="kwon"), fc)
    ref = direct_fuel_t(plan, kwon, Environment(kwon, fc))
    assert plan.total_fuel_t == pytest.approx(ref, rel=0.01)
