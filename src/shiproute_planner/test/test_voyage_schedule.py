"""Port-call parsing and the multi-port leg schedule (pure, no planning).

The schedule is checked against a brute-force search over the leg times and against the
closed form of the propeller law (fuel rate ~ v^3: the optimum sails every free leg at one
speed), not against numbers it printed.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from shiproute_planner.errors import InvalidVoyageError
from shiproute_planner.voyage.port_calls import parse_port_call
from shiproute_planner.voyage.schedule import SPEED_MARGIN, FuelRate, LegSpec, plan_schedule
from shiproute_planner.voyage.stage_length import (
    check_stage_hours,
    default_stage_hours,
    move_scale,
)

T0 = 1_780_272_000.0  # 2026-06-01T00:00Z
H = 3600.0
NM = 1852.0
CUBE = FuelRate(3.0, 12.0, (0.02, 0.0, 0.0, 0.0))  # t/h = 0.02 v^3, v in m/s


def test_port_call_forms():
    c = parse_port_call("Ningbo@1d..2d+6", T0)
    assert (c.port, c.earliest_s, c.latest_s, c.berth_s) == ("Ningbo", T0 + 86400,
                                                             T0 + 2 * 86400, 6 * H)
    c = parse_port_call("Xiamen@..2026-06-05T12:00Z", T0)
    assert c.earliest_s is None and c.latest_s == T0 + 4.5 * 86400
    c = parse_port_call("Yantian@3d", T0)  # one time: a latest arrival (the old PORT@TIME)
    assert c.earliest_s is None and c.latest_s == T0 + 3 * 86400
    c = parse_port_call("Singapore+12h", T0)
    assert c.latest_s is None and c.berth_s == 12 * H
    assert not parse_port_call("Rotterdam", T0).fixed


@pytest.mark.parametrize("text, words", [
    ("@1d", "names no port"),
    ("Ningbo@", "needs a time"),
    ("Ningbo@2d..1d", "after the latest"),
    ("Ningbo@yesterday", "ISO 8601"),
    ("Ningbo+x", "not a number"),
    ("Ningbo+-2", "must be in"),
    ("Ningbo@2026-05-30T00:00Z", "not after the departure"),
])
def test_port_call_errors_name_the_input(text, words):
    with pytest.raises(InvalidVoyageError, match=words):
        parse_port_call(text, T0)


def _fuel(legs, sched):
    return sum(t / H * float(CUBE.rate(np.array([leg.distance_m / t]))[0])
               for leg, t in zip(legs, sched.sail_s, strict=True) if leg.fixed_s is None)


def test_free_legs_sail_at_one_speed():
    """Propeller law without windows: equal marginal fuel per hour means equal speed."""
    legs = [LegSpec("A", 300 * NM), LegSpec("B", 1200 * NM), LegSpec("C", 2500 * NM)]
    sched = plan_schedule(legs, T0, T0 + 16 * 86400, CUBE)
    v = [leg.distance_m / t for leg, t in zip(legs, sched.sail_s, strict=True)]
    assert sched.feasible
    assert np.ptp(v) / np.mean(v) < 0.01
    assert sched.arrival_s[-1] == pytest.approx(T0 + 16 * 86400, abs=60)


def test_rate_fit_below_zero_at_the_slowest_speed_still_saves_fuel():
    """A cubic fitted to a ship's fuel rate may read below zero at its slowest speed (the
    supramax's does); its fuel per mile still rises with speed, so the legs use all the time
    to the RTA at one speed, as with the propeller law."""
    rate = FuelRate(1.7, 7.3, (0.02, 0.0, 0.0, -0.1))  # t/h, -0.002 at 1.7 m/s
    assert float(rate.rate(np.array([1.7]))[0]) < 0.0
    legs = [LegSpec("gate", 111 * NM), LegSpec("Santos", 812 * NM)]
    sched = plan_schedule(legs, T0, T0 + 108 * 3600, rate)
    v = [leg.distance_m / t for leg, t in zip(legs, sched.sail_s, strict=True)]
    assert sched.feasible
    assert sched.arrival_s[-1] == pytest.approx(T0 + 108 * 3600, abs=60)
    assert np.ptp(v) / np.mean(v) < 0.01


def test_schedule_matches_brute_force_with_a_window_and_berth():
    """A window that makes leg 1 fast: the schedule's fuel equals the best of a grid."""
    legs = [LegSpec("A", 600 * NM, latest_s=T0 + 40 * H, berth_s=10 * H),
            LegSpec("B", 1500 * NM, earliest_s=T0 + 150 * H, berth_s=6 * H),
            LegSpec("C", 900 * NM)]
    rta = T0 + 260 * H
    sched = plan_schedule(legs, T0, rta, CUBE)
    assert sched.feasible
    assert sched.arrival_s[0] <= T0 + 40 * H + 60
    assert sched.berth_start_s[1] >= T0 + 150 * H - 60
    assert sched.arrival_s[2] <= rta + 60
    # the schedule keeps 1 % of the leg's shortest time (>= 15 min) before a latest arrival
    margin_h = max(0.25, 0.01 * 600 * NM / (SPEED_MARGIN * CUBE.v_max_m_s) / H)
    best = np.inf
    for t1, t2 in itertools.product(np.linspace(20.0, 40.0 - margin_h, 41),
                                    np.arange(60.0, 200.0, 0.5)):
        arr2 = t1 + 10 + t2
        t3 = 260 - (max(arr2, 150) + 6)
        if t3 <= 0:
            continue
        f = sum(t * 0.02 * (leg.distance_m / (t * H)) ** 3
                for leg, t in zip(legs, (t1, t2, t3), strict=True))
        best = min(best, f)
    assert _fuel(legs, sched) == pytest.approx(best, rel=0.005)
    assert _fuel(legs, sched) <= best * 1.0001


def test_impossible_window_is_flagged_with_the_port_and_no_leg_is_impossible():
    legs = [LegSpec("Ningbo", 150 * NM), LegSpec("Xiamen", 500 * NM, latest_s=T0 + 10 * H),
            LegSpec("Gdansk", 2000 * NM)]
    sched = plan_schedule(legs, T0, T0 + 20 * 86400, CUBE)
    assert not sched.feasible
    assert any("Xiamen" in r and "latest arrival" in r for r in sched.reasons)
    for leg, t in zip(legs, sched.sail_s, strict=True):
        assert leg.distance_m / t <= CUBE.v_max_m_s + 1e-9


def test_berth_longer_than_rta_and_impossible_order_are_flagged():
    legs = [LegSpec("A", 100 * NM, berth_s=200 * H), LegSpec("B", 100 * NM)]
    sched = plan_schedule(legs, T0, T0 + 100 * H, CUBE)
    assert not sched.feasible and any("berth times" in r for r in sched.reasons)
    legs = [LegSpec("A", 100 * NM, earliest_s=T0 + 80 * H), LegSpec("B", 100 * NM,
                                                                    latest_s=T0 + 50 * H),
            LegSpec("C", 100 * NM)]
    sched = plan_schedule(legs, T0, T0 + 200 * H, CUBE)
    assert not sched.feasible and any("impossible order" in r for r in sched.reasons)


def test_stage_length_fits_the_voyage():
    assert default_stage_hours(13 * 86400) == 12.0  # an ocean crossing: the reference stage
    short = default_stage_hours(4 * H)
    assert 4 * H / (short * H) >= 9  # a 4-hour optimised part still gets >= 8 stages
    assert check_stage_hours(None) is None
    for bad in (0.0, 1000.0, float("nan")):
        with pytest.raises(InvalidVoyageError, match="stage hours"):
            check_stage_hours(bad)
    assert move_scale(24) == pytest.approx(1.0)
    assert move_scale(6) > move_scale(24) > move_scale(96)


def test_set_voyage_port_calls_round_trip_and_refusals():
    """SetVoyage's port calls (ROS-free half): checked, stored as the node parameter and
    read back unchanged; a window before departure or an unknown port is refused by name."""
    from shiproute_planner.errors import PlannerError
    from shiproute_planner.voyage.node_calls import node_port_calls
    from shiproute_planner.voyage.port_calls import PortCall
    from shiproute_planner.voyage_request import VoyageChange, check_voyage_request

    calls = (PortCall("Singapore", T0 + 7 * 86400, T0 + 10 * 86400, 12 * H),
             PortCall("Rotterdam", None, T0 + 27 * 86400, 0.0))

    def ask(c):
        return check_voyage_request(
            VoyageChange("Gdansk", 0.0, 0.0, T0 + 28 * 86400, "", "", port_calls=c),
            origin="Shanghai", ship="container_4600teu", objective="fuel", method="seed_ga",
            rta="2026-06-29T00:00:00Z", position=None, departure_time="2026-06-01T00:00:00Z",
            clock_s=0.0)

    checked = ask(calls)
    assert node_port_calls(str(checked.parameters["port_calls"]), T0) == calls
    assert "Singapore" in checked.message
    assert ask(()).parameters["port_calls"] == ""  # no calls: a direct voyage
    with pytest.raises(InvalidVoyageError, match="Singapore"):
        ask((PortCall("Singapore", None, T0 - 86400, 0.0),))
    with pytest.raises(PlannerError, match="Atlantis"):
        ask((PortCall("Atlantis Harbour", None, None, 0.0),))


@pytest.mark.parametrize("extra, words", [
    (["--via", "Ningbo@2d..1d"], "Ningbo"),
    (["--via", "Ningbo@2026-05-01T00:00Z"], "not after the departure"),
    (["--via", "Ningbo+lots"], "berth time"),
    (["--stage-hours", "0"], "stage-hours"),
    (["--stage-hours", "1000"], "stage-hours"),
    (["--rta-tolerance", "soon"], "duration"),
])
def test_cli_refuses_malformed_voyages_with_exit_2(extra, words, capsys, tmp_path):
    from shiproute_planner.cli.plan import main

    code = main(["--from", "Shanghai", "--to", "Gdansk", "--depart", "2026-06-01T00:00Z",
                 "--rta", "28d", "--out", str(tmp_path), *extra])
    assert code == 2
    assert words in capsys.readouterr().err


def test_calls_left_behind_are_dropped_under_way():
    from types import SimpleNamespace

    from shiproute_planner.voyage.node_calls import calls_ahead
    from shiproute_planner.voyage.port_calls import PortCall

    calls = (PortCall("Ningbo"), PortCall("Singapore", None, T0 + 9 * 86400, 12 * H))
    prev = SimpleNamespace(extra={"port_calls": [
        {"port": "Ningbo", "departure_s": T0 + 0.4 * 86400},
        {"port": "Singapore", "departure_s": T0 + 8 * 86400}]})
    assert calls_ahead(calls, prev, T0 + 86400) == calls[1:]
    assert calls_ahead(calls, prev, T0 + 0.2 * 86400) == calls
    assert calls_ahead(calls, None, T0 + 86400) == calls
