"""The frozen planning API: `VoyageRequest` + `PlanOptions` -> `planning.plan`; the keyword
wrapper, the CLI/fleet request and the node's parameters all build the same two objects."""

from __future__ import annotations

import dataclasses
import inspect
from datetime import timedelta

import numpy as np
import pytest
from shiproute_planner.errors import InvalidVoyageError
from shiproute_planner.objectives import Economics
from shiproute_planner.plan_prepare import ship_choice
from shiproute_planner.plan_request import build_request
from shiproute_planner.planning import plan, plan_voyage
from shiproute_planner.request import PlanOptions, VoyageRequest, voyage_times, with_fields
from shiproute_planner.ros.plan_call import node_request
from shiproute_planner.ship import PhysicsModel, load_ship

JUNE = "2026-06-01T00:00Z"
# the positional arguments of `plan_voyage` that become other fields: the times (POSIX s),
# `via_rta` (via_rta_s) and the forecast (a third argument of `plan`, not a field)
RENAMED = {"depart": "depart_s", "rta": "rta_s", "via_rta": "via_rta_s"}


def _track(p):
    return np.array([(w.lat_deg, w.lon_deg, w.shaft_rpm, w.time_s) for w in p.waypoints])


def test_every_plan_voyage_keyword_is_a_request_or_option_field():
    """A keyword added to `plan_voyage` without a field (or the other way round) fails here."""
    keywords = set(inspect.signature(plan_voyage).parameters) - {"forecast"}
    fields = ({f.name for f in dataclasses.fields(VoyageRequest)}
              | {f.name for f in dataclasses.fields(PlanOptions)})
    assert {RENAMED.get(k, k) for k in keywords} == fields
    voyage = {f.name for f in dataclasses.fields(VoyageRequest)}
    options = {f.name for f in dataclasses.fields(PlanOptions)}
    assert not voyage & options  # one home per keyword


def test_request_and_options_are_frozen():
    req = VoyageRequest("Busan", "Long Beach", 0.0, 86400.0, "container_4600teu")
    with pytest.raises(dataclasses.FrozenInstanceError):
        req.rta_s = 1.0  # type: ignore[misc]
    with pytest.raises(dataclasses.FrozenInstanceError):
        PlanOptions().budget_s = 1.0  # type: ignore[misc]


def test_voyage_times_take_a_time_or_a_duration():
    # 2026-06-01T00:00Z = 1780272000 s (20606 days after the epoch)
    assert voyage_times(JUNE, timedelta(days=2)) == (1780272000.0, 1780272000.0 + 2 * 86400)
    assert voyage_times(JUNE, "2026-06-03T00:00Z") == (1780272000.0, 1780444800.0)


def test_with_fields_routes_each_keyword_and_refuses_unknown_names():
    req = VoyageRequest("Busan", "Long Beach", 0.0, 86400.0, "container_4600teu")
    r2, o2 = with_fields(req, PlanOptions(), zones=["a.geojson"], budget_s=7.0,
                         clearance_nm=2.0)
    assert r2.zones == ("a.geojson",) and r2.clearance_nm == 2.0 and o2.budget_s == 7.0
    assert req.zones is None  # the originals are untouched
    with pytest.raises(TypeError, match="budget_sec"):
        with_fields(req, PlanOptions(), budget_sec=1.0)


def test_cli_request_and_node_parameters_make_the_same_voyage():
    """`shiproute plan` and the planner node build one `VoyageRequest` from the same words."""
    cli = build_request(origin="Busan", destination="Long Beach", depart=JUNE,
                        rta="2026-06-14T00:00Z", via=["Yokohama@..2026-06-04T00:00Z+12"],
                        objective="cost", model="kwon", loading="ballast",
                        fuel_type="MGO", fuel_price_usd_per_t=700.0, rta_tolerance="10m")
    params = {"destination": "Long Beach", "rta": "2026-06-14T00:00Z",
              "ship": "container_4600teu", "rta_tolerance_s": 600.0, "objective": "cost",
              "fuel_type": "MGO", "fuel_price_usd_per_t": 700.0, "charter_usd_per_day": -1.0,
              "ship_model": "kwon", "loading": "ballast", "bathymetry_files": "",
              "default_bathymetry": False, "ukc_margin_m": 1.0, "zones_files": "",
              "clearance_nm": 0.0, "approach_files": ""}
    node = node_request(params.__getitem__, origin="Busan", depart_s=cli.depart_s, rta_s=None,
                        objective="", calls=cli.port_calls)
    from_cli = cli.voyage_request()
    # the CLI keeps the vias as named ports beside their calls; the node names only calls
    assert dataclasses.replace(from_cli, via=(), via_rta_s=()) == node
    assert [c.berth_s for c in node.port_calls] == [12 * 3600.0]
    assert node.economics == Economics("MGO", 700.0, None)


def test_physics_direct_is_the_ship_physics_in_its_loading():
    ship, choice, loading = ship_choice("container_4600teu", "physics-direct", "")
    assert isinstance(ship, PhysicsModel) and (choice, loading) == ("", "")
    assert ship.ship == load_ship("container_4600teu")
    assert ship_choice("container_4600teu", "fast", "ballast") == (
        "container_4600teu", "physics", "ballast")
    with pytest.raises(InvalidVoyageError, match="not with a model"):
        ship_choice(PhysicsModel(load_ship("container_4600teu")), "physics-direct", "")


def test_plan_and_plan_voyage_give_the_same_plan(land_mask):
    """A fixed number of route evaluations makes a run reproducible: the keyword wrapper
    and the request API must then give the identical plan."""
    depart_s, rta_s = voyage_times(JUNE, timedelta(days=8))
    request = VoyageRequest("New York", "Lisbon", depart_s, rta_s, "container_4600teu")
    options = PlanOptions(budget_s=float("inf"), max_evaluations=1500, seed=3, land=land_mask)
    a = plan(request, options)
    b = plan_voyage("New York", "Lisbon", JUNE, timedelta(days=8), "container_4600teu",
                    budget_s=float("inf"), max_evaluations=1500, seed=3, land=land_mask)
    assert np.array_equal(_track(a), _track(b), equal_nan=True)
    assert a.total_fuel_t == b.total_fuel_t and a.evaluations == b.evaluations
    assert a.evaluations >= 1500  # the budget was spent, not skipped


def test_a_bad_request_names_the_input(land_mask):
    request = VoyageRequest("Busan", "Long Beach", 1000.0, 500.0, "container_4600teu")
    with pytest.raises(InvalidVoyageError, match="RTA must be after"):
        plan(request, PlanOptions(land=land_mask, budget_s=0.0, max_generations=0))
    late_via = VoyageRequest("Busan", "Long Beach", 1780272000.0, 1780272000.0 + 13 * 86400,
                             "container_4600teu", via=("Yokohama",), via_rta_s=(1.0,))
    with pytest.raises(InvalidVoyageError, match="via Yokohama: RTA is not after"):
        plan(late_via, PlanOptions(land=land_mask, budget_s=0.0, max_generations=0))
