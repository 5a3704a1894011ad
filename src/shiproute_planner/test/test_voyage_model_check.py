"""A voyage is refused when the ship model its plans would use does not exist: the node's
ship_model parameter, else the ship file's performance_model entry (issue 16: "model exists")."""

from __future__ import annotations

from pathlib import Path

import pytest
from shiproute_planner.checks.voyage import check_voyage
from shiproute_planner.learned.errors import ModelFileError
from shiproute_planner.voyage_request import VoyageChange, check_voyage_request

DEPART_S = 1780509600.0  # 2026-06-03T18:00:00Z
RTA_S = DEPART_S + 13 * 86400


def _ship_naming(tmp_path: Path, model: str) -> str:
    """The bundled 4,600 TEU ship file with a performance_model entry of its own."""
    import shiproute_planner.ships as ships

    text = (Path(ships.__file__).parent / "container_4600teu.yaml").read_text()
    path = tmp_path / "ship_with_model.yaml"
    path.write_text(text + f"\nperformance_model: {model}\n")
    return str(path)


def test_ship_file_naming_a_missing_model_is_refused(tmp_path: Path, land_mask,
                                                     monkeypatch) -> None:
    ship = _ship_naming(tmp_path, "learned:no_such_model.nc")
    with pytest.raises(ModelFileError, match=r"no_such_model\.nc"):
        check_voyage("Busan", "Long Beach", DEPART_S, RTA_S, ship, land=land_mask)
    # the node's ship_model parameter overrides the file's entry: then the voyage is valid
    # (the ship's top speed is beside the point here: its tabulation takes seconds)
    monkeypatch.setattr("shiproute_planner.checks.voyage.max_calm_speed_kn", lambda _s: 20.0)
    check = check_voyage("Busan", "Long Beach", DEPART_S, RTA_S, ship, land=land_mask,
                         ship_model="physics")
    assert check.destination.name.startswith("Long Beach")


def test_missing_model_parameter_file_is_refused(land_mask, tmp_path: Path) -> None:
    missing = tmp_path / "gone.nc"
    with pytest.raises(ModelFileError, match=r"gone\.nc"):
        check_voyage("Busan", "Long Beach", DEPART_S, RTA_S, "container_4600teu",
                     land=land_mask, ship_model=f"profile:{missing}")


def test_set_voyage_request_passes_the_node_model(tmp_path: Path) -> None:
    req = VoyageChange("Long Beach", 0.0, 0.0, RTA_S, "", "")
    with pytest.raises(ModelFileError, match=r"gone\.nc"):
        check_voyage_request(req, origin="Busan", ship="container_4600teu", objective="fuel",
                             method="seed_ga", rta="", position=None,
                             departure_time="2026-06-03T18:00:00Z", clock_s=0.0,
                             ship_model=f"learned:{tmp_path / 'gone.nc'}")
