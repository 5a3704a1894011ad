"""Each input defect of issue 16, at the library level (the ROS-level suite is
tests/test_bad_input_ros.py): what used to get through is now refused with a reason naming the
input, or planned best effort and flagged."""

from __future__ import annotations

import math

import numpy as np
import pytest
from shiproute_planner.checks.forecast_wire import (
    MAX_CYCLE_STORAGE_BYTES,
    check_not_older,
    check_slice_count,
    check_slice_fields,
)
from shiproute_planner.checks.ship_state import check_ship_state
from shiproute_planner.checks.voyage import check_voyage
from shiproute_planner.errors import (
    ForecastCycleError,
    InvalidVoyageError,
    PortNotFoundError,
    PositionOnLandError,
    ShipStateError,
    StaleForecastError,
)
from shiproute_planner.ros.cycle_assembler import CycleAssembler
from shiproute_planner.ros.cycle_packer import CyclePacker, SliceFields
from shiproute_planner.ros.intake_keys import RejectedKeys, assembly_key
from shiproute_planner.ship.errors import UnknownShipError
from shiproute_planner.voyage_params import check_parameter
from shiproute_weather.contract.canonical import Grid

REF_S = 1780488000.0  # 2026-06-03T12:00Z
PACIFIC = Grid(10.0, 5.0, 11, 115.0, 5.0, 27)
WIND = ("eastward_wind", "northward_wind")


def _slice(grid: Grid = PACIFIC, *, index: int = 0, count: int = 1, valid_s: float = REF_S,
           ref_s: float = REF_S, value: float = 3.0, cells: int | None = None,
           cycle: str = "c1", publication: str = "") -> SliceFields:
    n = grid.n_lat * grid.n_lon if cells is None else cells
    fields = tuple((name, np.full(n, value, dtype=np.float32)) for name in WIND)
    return SliceFields(cycle, index, count, valid_s, grid, fields, (), ref_s, publication)


@pytest.mark.parametrize(("grid", "word"), [
    (Grid(10.0, 0.5, 0, 115.0, 0.5, 0), "shape"),              # zero-size grid
    (Grid(10.0, math.nan, 11, 115.0, 5.0, 27), "dlat_deg"),   # NaN spacing
    (Grid(10.0, 5.0, 11, 115.0, 0.0, 27), "dlon_deg"),        # zero spacing: division by zero
    (Grid(10.0, -5.0, 11, 115.0, 5.0, 27), "dlat_deg"),       # descending
    (Grid(-90.0, 1e-6, 1_000_000, 0.0, 1e-6, 1_000_000), "cells"),  # 8 TiB declared
    (Grid(80.0, 5.0, 11, 115.0, 5.0, 27), "latitudes"),       # past the pole
])
def test_bad_grids_refused_before_allocation(grid: Grid, word: str) -> None:
    s = _slice(grid, cells=16)
    with pytest.raises(ForecastCycleError, match=word):
        check_slice_fields(s)


def test_declared_size_must_equal_the_data() -> None:
    with pytest.raises(ForecastCycleError, match="has 16 values, expected 297"):
        check_slice_fields(_slice(cells=16))


def test_cycle_storage_is_bounded() -> None:
    big = Grid(-80.0, 0.05, 1999, 0.0, 0.05, 2000)  # 4.0 M cells per slice: allowed alone
    s = _slice(big, count=500, cells=4)
    with pytest.raises(ForecastCycleError, match="MiB"):
        check_slice_fields(s)
    assert MAX_CYCLE_STORAGE_BYTES < 500 * 1999 * 2000 * 2 * 2


@pytest.mark.parametrize(("value", "word"), [(math.inf, "infinite"), (250.0, "spans")])
def test_values_finite_or_nan_and_in_range(value: float, word: str) -> None:
    with pytest.raises(ForecastCycleError, match=word):
        check_slice_fields(_slice(value=value))
    check_slice_fields(_slice(value=math.nan))  # missing everywhere is allowed


@pytest.mark.parametrize(("valid_s", "ref_s"), [(0.0, REF_S), (math.nan, REF_S),
                                                 (REF_S, -5.0), (5e9, REF_S)])
def test_times_in_a_sane_window(valid_s: float, ref_s: float) -> None:
    with pytest.raises(ForecastCycleError, match="time"):
        check_slice_fields(_slice(valid_s=valid_s, ref_s=ref_s))


def test_slice_count_bounded() -> None:
    for n in (0, 10**6):
        with pytest.raises(ForecastCycleError, match="slice_count"):
            check_slice_count("c", n)


def test_older_model_run_refused_unless_asked() -> None:
    with pytest.raises(StaleForecastError, match="older"):
        check_not_older("old", REF_S - 6 * 3600, "new", REF_S)
    check_not_older("same", REF_S, "new", REF_S)  # a reload of the run in force
    check_not_older("newer", REF_S + 6 * 3600, "new", REF_S)


def test_good_slice_accepted_and_packs() -> None:
    s = _slice()
    check_slice_fields(s)
    packer = CyclePacker(s)
    packer.add(0, s)
    sampler = packer.result()
    out = sampler.sample(np.array([150.0]), np.array([30.0]), np.array([REF_S]))
    assert abs(out["eastward_wind"][0] - 3.0) < 3e-3  # half precision of 3.0


def test_publications_never_merge_and_reloads_are_new() -> None:
    """A restarted publisher's slices never complete a dead one's cycle; a reload of the same
    cycle (a new publication) is assembled again."""
    asm: CycleAssembler[SliceFields] = CycleAssembler()
    dead, alive = assembly_key("c1", "dead-1"), assembly_key("c1", "alive-1")
    asm.announce(dead, 2)
    assert asm.add_slice(dead, 0, 2, _slice(index=0, count=2)) is None
    asm.announce(alive, 2)
    assert asm.add_slice(alive, 1, 2, _slice(index=1, count=2, valid_s=REF_S + 3600)) is None
    again = assembly_key("c1", "alive-2")
    asm.announce(again, 1)
    assert asm.add_slice(again, 0, 1, _slice()) is not None
    reload = assembly_key("c1", "alive-3")
    asm.announce(reload, 1)
    assert asm.add_slice(reload, 0, 1, _slice()) is not None


def test_evicted_partial_cycles_are_reported() -> None:
    evicted: list[tuple[str, int]] = []
    asm: CycleAssembler[SliceFields] = CycleAssembler(
        max_pending_cycles=1, on_evict=lambda k, n: evicted.append((k, n)))
    asm.announce("a", 3)
    asm.add_slice("a", 0, 3, _slice(index=0, count=3))
    asm.announce("b", 3)
    assert evicted == [("a", 1)]


def test_rejected_keys_bounded() -> None:
    keys = RejectedKeys(capacity=3)
    for k in range(10):
        keys.add(str(k), f"reason {k}")
    assert "9" in keys and "0" not in keys and keys.reason("8") == "reason 8"


@pytest.mark.parametrize(("name", "value", "word"), [
    ("stage_hours", 1000.0, "stage_hours"), ("stage_hours", 0.05, "stage_hours"),
    ("budget_s", 1e5, "budget_s"), ("budget_s", math.nan, "budget_s"),
    ("rng_seed", -1, "rng_seed"), ("rta", "yesterday", "rta"), ("rta", "1900-01-01Z", "rta"),
    ("destination", " ", "destination"), ("objective", "speed", "objective"),
    ("replan_cross_track_nm", math.inf, "replan_cross_track_nm"),
])
def test_parameters_have_ranges_with_reasons(name: str, value: object, word: str) -> None:
    reason = check_parameter(name, value)
    assert reason is not None and word in reason


def test_default_parameters_accepted() -> None:
    for name, value in (("stage_hours", 12.0), ("stage_hours", 0.0), ("budget_s", 3.0),
                        ("rng_seed", 0), ("rta", "2026-03-16T18:00:00Z"),
                        ("min_replan_interval_s", 3600.0)):
        assert check_parameter(name, value) is None


@pytest.mark.parametrize(("lat", "lon", "t", "extra", "word"), [
    (math.nan, 129.0, REF_S, {}, "latitude"), (91.0, 129.0, REF_S, {}, "latitude"),
    (35.0, math.inf, REF_S, {}, "longitude"), (35.0, 129.0, 0.0, {}, "1970"),
    (35.0, 129.0, REF_S + 86400, {}, "ahead"), (35.0, 129.0, REF_S, {"sog_kn": math.inf},
                                                 "sog_kn"),
])
def test_bad_ship_states_refused(lat, lon, t, extra, word) -> None:
    with pytest.raises(ShipStateError, match=word):
        check_ship_state(lat, lon, t, extra, clock_s=REF_S)


def test_ship_state_without_clock_checks_the_stamp_only() -> None:
    fix = check_ship_state(35.0, 129.0, REF_S, {"sog_kn": math.nan}, clock_s=0.0)
    assert (fix.lat_deg, fix.lon_deg, fix.time_s) == (35.0, 129.0, REF_S)


@pytest.mark.parametrize(("dest", "depart", "rta", "ship", "error"), [
    ("Atlantis", REF_S, REF_S + 13 * 86400, "container_4600teu", PortNotFoundError),
    ("39.0,-100.0", REF_S, REF_S + 13 * 86400, "container_4600teu", PositionOnLandError),
    ("Long Beach", REF_S, REF_S - 86400, "container_4600teu", InvalidVoyageError),
    ("Long Beach", REF_S, math.nan, "container_4600teu", InvalidVoyageError),
    ("Long Beach", REF_S, REF_S + 13 * 86400, "flying_dutchman", UnknownShipError),
])
def test_bad_voyages_refused(land_mask, dest, depart, rta, ship, error) -> None:
    with pytest.raises(error):
        check_voyage("Busan", dest, depart, rta, ship, land=land_mask)


def test_unreachable_rta_is_flagged_not_refused(land_mask) -> None:
    c = check_voyage("Busan", "Long Beach", REF_S, REF_S + 3600, "container_4600teu",
                     land=land_mask)
    assert not c.rta_reachable and "RTA unreachable" in c.rta_warning
    # independent reference: haversine on a 6,371 km sphere (within 0.6 % of the ellipsoid)
    p1, p2 = np.radians([c.origin.lat_deg, c.origin.lon_deg, c.destination.lat_deg,
                         c.destination.lon_deg]).reshape(2, 2)
    h = (np.sin((p2[0] - p1[0]) / 2) ** 2
         + np.cos(p1[0]) * np.cos(p2[0]) * np.sin((p2[1] - p1[1]) / 2) ** 2)
    sphere_nm = 2 * 6371.0 * np.arcsin(np.sqrt(h)) / 1.852
    assert c.great_circle_nm == pytest.approx(sphere_nm, rel=0.006)
    assert c.required_speed_kn == pytest.approx(c.great_circle_nm / 1.0)  # in one hour
    # the reference ship makes 17.7 kn at 77 rpm (ship README); at 104 rpm it is faster
    assert 17.7 < c.max_speed_kn < 30.0
    ok = check_voyage("Busan", "Long Beach", REF_S, REF_S + 13 * 86400, "container_4600teu",
                      land=land_mask)
    assert ok.rta_reachable and ok.rta_warning == ""


def test_impossible_rta_gives_flagged_best_effort_plan(land_mask) -> None:
    """An RTA one hour away used to fail with InputRangeError 'stw_m_s ... 452.5'."""
    from shiproute_planner.planning import plan_voyage

    plan = plan_voyage("Busan", "Long Beach", REF_S, REF_S + 3600, "container_4600teu", None,
                       budget_s=1.0, max_generations=3, land=land_mask)
    assert not plan.feasible
    assert any("RTA" in r for r in plan.infeasible_reasons), plan.infeasible_reasons
    assert any("RTA unreachable" in w for w in plan.warnings)
    assert plan.eta_s > plan.rta_s
    # best effort: the approaches at full RPM (104, the ship file's engine.rpm_max)
    assert max(w.shaft_rpm for w in plan.waypoints[:-1]) >= 0.95 * 104.0


def test_stage_hours_bounded_in_the_library(land_mask) -> None:
    from shiproute_planner.errors import ParameterError
    from shiproute_planner.planning import plan_voyage

    with pytest.raises(ParameterError, match="stage_hours"):
        plan_voyage("Busan", "Long Beach", REF_S, REF_S + 13 * 86400, "container_4600teu", None,
                    stage_hours=1000.0, land=land_mask)



def test_completed_cycle_supersedes_older_incomplete_ones() -> None:
    """An older publication still incomplete when a newer one completes is dropped at once
    (its sampler array would otherwise stay resident until evicted)."""
    evicted: list[tuple[str, int]] = []
    asm: CycleAssembler[SliceFields] = CycleAssembler(on_evict=lambda k, n: evicted.append((k, n)))
    asm.announce("old", 2)
    asm.add_slice("old", 0, 2, _slice(index=0, count=2))
    asm.announce("new", 1)
    assert asm.add_slice("new", 0, 1, _slice()) is not None
    assert evicted == [("old", 1)]
    assert asm.missing("old") is None
