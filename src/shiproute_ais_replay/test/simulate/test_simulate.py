"""Voyage simulation in calm water checked against the ship model evaluated directly."""

from __future__ import annotations

import json
import math
from datetime import UTC, datetime
from pathlib import Path

import numpy as np
import pytest
from ais_replay_helpers import EQUATOR_DEG_M, meridian_arc_m
from shiproute_ais_replay.bag.bagreader import BagReader
from shiproute_ais_replay.bag.shipstate import from_rosbags
from shiproute_ais_replay.cli import main
from shiproute_ais_replay.simulate.simulator import SimulationOptions, VoyageSimulator
from shiproute_ais_replay.simulate.voyage_input import great_circle, read_rtz
from shiproute_core.topics import SHIP_STATE
from shiproute_core.units import M_PER_NM

ship_mod = pytest.importorskip("shiproute_planner.ship")
DEG_M = EQUATOR_DEG_M  # one degree of longitude along the WGS 84 equator [m]
T0 = 1_772_668_800.0  # 2026-03-05T00:00:00Z


@pytest.fixture(scope="module")
def ship_model():
    ship = ship_mod.load_ship("container_4600teu")
    return ship, ship_mod.PhysicsModel(ship)


def test_great_circle_calm_matches_model(ship_model):
    ship, model = ship_model
    perf = model.evaluate(np.array(70.0), np.array(90.0), ship_mod.SeaState.calm(()))
    sog, fuel = float(perf.sog_m_s), float(perf.fuel_t_per_h)
    opts = SimulationOptions(departure_s=T0, rate_hz=0.1, model_step_s=600.0, noise=False)
    sim = VoyageSimulator(great_circle(0.0, 0.0, 0.0, 1.0, 70.0), model, ship, opts)
    states = list(sim.states())
    duration = DEG_M / sog
    assert sim.summary.arrived
    assert sim.summary.duration_s == pytest.approx(duration, rel=1e-6)
    assert sim.summary.fuel_t == pytest.approx(fuel * duration / 3600, rel=1e-6)
    assert sim.summary.distance_nm == pytest.approx(DEG_M / M_PER_NM, rel=1e-9)
    # one state every 10 s from departure, plus the arrival state
    assert len(states) == math.floor(duration / 10) + 1 + 1
    assert states[1].time_ns - states[0].time_ns == 10 * 10**9
    mid = states[len(states) // 2]
    assert mid.sog_kn == pytest.approx(sog * 3600 / M_PER_NM)
    assert mid.shaft_rpm == 70.0 and mid.heading_deg == pytest.approx(90.0)
    assert mid.latitude_deg == pytest.approx(0.0, abs=1e-9)
    assert mid.longitude_deg == pytest.approx((mid.time_ns / 1e9 - T0) * sog / DEG_M, rel=1e-9)
    assert (states[-1].latitude_deg, states[-1].longitude_deg) == (0.0, 1.0)
    assert mid.draft_fore_m == ship.condition.draft_fore_m


RTZ_TEMPLATE = """<?xml version="1.0" encoding="UTF-8"?>
<route xmlns="http://www.cirm.org/RTZ/1/2" version="1.2">
  <routeInfo routeName="test"/>
  <waypoints>
    <waypoint id="1"><position lat="0.0" lon="0.0"/></waypoint>
    <waypoint id="2"><position lat="0.0" lon="0.5"/></waypoint>
    <waypoint id="3"><position lat="0.5" lon="0.5"/></waypoint>
  </waypoints>
  <schedules><schedule id="1"><calculated>
    <scheduleElement waypointId="1" etd="2026-03-05T00:00:00Z" rpm="60"/>
    <scheduleElement waypointId="2"/>
    <scheduleElement waypointId="3" eta="{eta}"/>
  </calculated></schedule></schedules>
</route>
"""


def test_rtz_schedule_rpm_then_eta(tmp_path: Path, ship_model):
    ship, model = ship_model
    calm = ship_mod.SeaState.calm(())
    v60 = float(model.evaluate(np.array(60.0), np.array(90.0), calm).sog_m_s)
    v70 = float(model.evaluate(np.array(70.0), np.array(0.0), calm).sog_m_s)
    # feasible ETA: first leg at 60 rpm, second leg (due north) at the 70 rpm speed
    eta_s = round(T0 + 0.5 * DEG_M / v60 + meridian_arc_m(0.0, 0.5) / v70)
    eta_iso = datetime.fromtimestamp(eta_s, tz=UTC).isoformat().replace("+00:00", "Z")
    path = tmp_path / "r.rtz"
    path.write_text(RTZ_TEMPLATE.replace("{eta}", eta_iso))
    plan = read_rtz(path)
    assert plan.departure_s == T0
    assert plan.leg_rpm[0] == 60.0 and math.isnan(plan.leg_rpm[1])
    assert plan.leg_eta_s[1] == eta_s
    opts = SimulationOptions(departure_s=plan.departure_s, rate_hz=0.01, noise=False)
    sim = VoyageSimulator(plan, model, ship, opts)
    states = list(sim.states())
    assert sim.summary.arrived
    # second leg re-plans the speed every step so the ship arrives at the ETA
    assert sim.summary.duration_s == pytest.approx(eta_s - T0, abs=60)
    first_leg = [s for s in states if s.longitude_deg < 0.49]
    assert {s.shaft_rpm for s in first_leg} == {60.0}
    second_leg = [s for s in states if s.latitude_deg > 0.01 and s.shaft_rpm > 0]
    assert np.mean([s.shaft_rpm for s in second_leg]) == pytest.approx(70.0, abs=1.0)


def test_simulate_cli_writes_bag(tmp_path: Path, capsys):
    out = tmp_path / "sim"
    rc = main(["simulate", str(out), "--from-lat", "0", "--from-lon", "0", "--to-lat", "0",
               "--to-lon", "0.2", "--depart", "2026-03-05T00:00:00Z", "--rpm", "70",
               "--rate-hz", "0.2", "--seed", "3"])
    assert rc == 0
    report = json.loads(capsys.readouterr().out)
    assert report["arrived"]
    reader = BagReader(out)
    states = [from_rosbags(reader.deserialize(m)) for m in reader.messages()
              if m.topic == SHIP_STATE]
    assert len(states) == report["states"]
    # sensor noise is small: GPS ~3 m, SOG 0.05 kn
    lat = np.array([s.latitude_deg for s in states[:-1]])
    assert np.abs(lat).max() < 20 / meridian_arc_m(0.0, 1.0)
    assert np.std([s.sog_kn for s in states[:-1]]) < 0.1


def test_plan_summary_json_uses_sibling_rtz(tmp_path: Path):
    from shiproute_ais_replay.errors import SimulationError
    from shiproute_ais_replay.simulate.voyage_input import read_voyage

    rtz = RTZ_TEMPLATE.replace("{eta}", "2026-03-05T06:00:00Z")
    (tmp_path / "plan_x.json").write_text(json.dumps(
        {"ship": "container_4600teu", "legs": [{"leg": 0, "lat_deg": 0.0, "lon_deg": 0.0}]}))
    with pytest.raises(SimulationError, match="arrival point"):
        read_voyage(tmp_path / "plan_x.json")
    (tmp_path / "plan_x.rtz").write_text(rtz)
    plan = read_voyage(tmp_path / "plan_x.json")
    assert plan.ship == "container_4600teu"
    assert list(plan.lat_deg) == [0.0, 0.0, 0.5] and plan.leg_rpm[0] == 60.0
