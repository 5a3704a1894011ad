"""The planner's ship-model choice: --model / ship_model / ship-file entry, and refusals."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from shiproute_planner.errors import InvalidVoyageError
from shiproute_planner.learned.features import FEATURES, ship_identity
from shiproute_planner.learned.model import LearnedModel, Network
from shiproute_planner.learned.select import resolve_model
from shiproute_planner.plan_setup import chosen_model as _chosen_model
from shiproute_planner.ship import ShipFileError, load_ship
from shiproute_planner.ship.loading import ship_file_path
from shiproute_planner.voyage_params import check_parameter


def _zero_model(ship, path: Path) -> Path:
    """A learned model whose residual is zero: it must reproduce the ship file's physics."""
    nf, h = len(FEATURES), 4
    net = Network(np.zeros((2, nf, h)), np.zeros((2, h)), np.zeros((2, h)), np.zeros(2), 0.0, 1.0)
    c = ship.condition
    lo = np.array([8.0, 11.0, -1.0, 0.0, -1.0, 0.0, -1.0, 3.0])  # a plausible training box
    hi = np.array([22.0, 13.0, 2.0, 25.0, 1.0, 8.0, 1.0, 14.0])
    LearnedModel(ship.name, ship_identity(ship), np.zeros(nf), np.ones(nf), lo, hi, net, net,
                 c.draft_fore_m, c.draft_aft_m).save(path)
    return path


def test_zero_residual_learned_tables_equal_the_physics_tables(tmp_path: Path) -> None:
    ship = load_ship("container_4600teu")
    fm, notes = resolve_model(ship, f"learned:{_zero_model(ship, tmp_path / 'z.nc')}")
    phys, none = resolve_model(ship, "physics")
    assert none == () and "learned from records" in notes[0]
    rpm = np.linspace(50, 95, 10)
    from shiproute_planner.ship import SeaState

    a = fm.evaluate(rpm, 0.0, SeaState.calm(10))
    b = phys.evaluate(rpm, 0.0, SeaState.calm(10))
    # within the kernel solve's own tolerance (Newton steps below 5e-3 m/s)
    np.testing.assert_allclose(a.stw_m_s, b.stw_m_s, rtol=1e-4)
    np.testing.assert_allclose(a.fuel_t_per_h, b.fuel_t_per_h, rtol=1e-4)


def test_model_of_another_ship_is_refused_before_planning(tmp_path: Path) -> None:
    path = _zero_model(load_ship("container_4600teu"), tmp_path / "m.nc")
    with pytest.raises(InvalidVoyageError, match="trained for ship 'container_4600teu', not "
                                                 "for 'vlcc_270k'"):
        _chosen_model("vlcc_270k", f"learned:{path}")
    with pytest.raises(InvalidVoyageError, match="does not exist"):
        _chosen_model("container_4600teu", f"learned:{tmp_path / 'none.nc'}")
    with pytest.raises(InvalidVoyageError, match="use physics, kwon"):
        _chosen_model("container_4600teu", "neural")


def test_ship_file_entry_and_node_parameter(tmp_path: Path) -> None:
    text = ship_file_path("container_4600teu").read_text()
    _zero_model(load_ship("container_4600teu"), tmp_path / "m.nc")
    f = tmp_path / "ship.yaml"
    f.write_text(text + "\nperformance_model: learned:m.nc\n")
    spec = load_ship(f)
    assert spec.performance_model == f"learned:{tmp_path / 'm.nc'}"  # relative to the file
    _, notes = _chosen_model(spec, "")
    assert any("learned from records" in n for n in notes)
    f.write_text(text + "\nperformance_model: neural\n")
    with pytest.raises(ShipFileError, match="performance_model"):
        load_ship(f)
    assert check_parameter("ship_model", "") is None
    assert check_parameter("ship_model", "kwon") is None
    assert "does not exist" in check_parameter("ship_model", "learned:/nonexistent.nc")
    assert "must be" in check_parameter("ship_model", "learned")


def test_plan_cli_reports_a_bad_model_without_traceback(capsys) -> None:
    from shiproute_planner.cli.plan import main

    rc = main(["--from", "35,160", "--to", "38,190", "--depart", "2026-03-10T00:00Z",
               "--rta", "4d", "--model", "learned:/nonexistent/model.nc", "--no-plot"])
    err = capsys.readouterr().err
    assert rc == 2 and "does not exist" in err and "Traceback" not in err
