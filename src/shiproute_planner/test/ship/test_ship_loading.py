"""Ship files: bundled ships load and validate; bad files raise errors naming file and key."""

import pytest
from shiproute_planner.ship import (
    ShipFileError,
    UnknownShipError,
    bundled_ships,
    load_ship,
    parse_ship,
)
from shiproute_planner.ship.loading import ship_file_path

BUNDLED = ("container_4600teu", "vlcc_270k", "bulk_supramax", "container_348m")


def test_bundled_ships_present_and_loadable():
    assert set(BUNDLED) <= set(bundled_ships())
    for name in BUNDLED:
        ship = load_ship(name)
        assert ship.name == name
        assert ship.sources, f"{name} must cite sources"
        for cond in ship.conditions:
            assert load_ship(name, cond).condition.name == cond


def test_reference_ship_particulars():
    s = load_ship("container_4600teu")
    assert (s.hull.lpp_m, s.hull.breadth_m, s.hull.depth_m) == (241.0, 37.5, 19.5)
    big = load_ship("container_348m")
    assert (big.hull.lpp_m, big.hull.breadth_m, big.mean_draft_m) == (348.0, 51.2, 13.5)
    assert big.condition.displacement_t == 169700


def _text() -> str:
    return ship_file_path("container_4600teu").read_text()


def test_missing_key_names_file_and_key():
    bad = _text().replace("  mcr_kw: 36560\n", "")
    with pytest.raises(ShipFileError, match=r"my\.yaml: key 'engine\.mcr_kw': is required"):
        parse_ship(bad, "my.yaml")


def test_out_of_range_value_is_reported():
    bad = _text().replace("pitch_ratio: 0.85", "pitch_ratio: 3.0")
    with pytest.raises(ShipFileError, match=r"propeller\.pitch_ratio.*outside the valid range"):
        parse_ship(bad, "my.yaml")


def test_wrong_type_and_bad_sfoc_curve():
    with pytest.raises(ShipFileError, match=r"hull\.breadth_m.*must be a number"):
        parse_ship(_text().replace("breadth_m: 37.5", "breadth_m: wide"), "x.yaml")
    bad = _text().replace("[0.10, 0.25, 0.35,", "[0.10, 0.35, 0.25,")
    with pytest.raises(ShipFileError, match=r"engine\.sfoc_load_fraction"):
        parse_ship(bad, "x.yaml")


def test_unknown_condition_ship_and_wind_set():
    with pytest.raises(ShipFileError, match="no condition 'arrival'"):
        load_ship("container_4600teu", "arrival")
    with pytest.raises(UnknownShipError, match="bundled"):
        load_ship("no_such_ship")
    bad = _text().replace("blendermann_container_loaded", "mystery")
    with pytest.raises(ShipFileError, match=r"windage\.coefficient_set.*unknown set 'mystery'"):
        parse_ship(bad, "x.yaml")


def test_invalid_yaml_and_implausible_displacement():
    with pytest.raises(ShipFileError, match="invalid YAML"):
        parse_ship("hull: [unclosed", "x.yaml")
    bad = _text().replace("displacement_t: 70300", "displacement_t: 20000")
    with pytest.raises(ShipFileError, match="block coefficient"):
        parse_ship(bad, "x.yaml")


def test_load_from_path_and_content_hash(tmp_path):
    p = tmp_path / "mine.yaml"
    p.write_text(_text())
    a, b = load_ship(p), load_ship("container_4600teu")
    assert a.content_hash == b.content_hash
    assert load_ship(p, "ballast").content_hash != a.content_hash


def test_ship_library_does_not_import_rclpy():
    import subprocess
    import sys

    code = "import sys, shiproute_planner.ship; print('rclpy' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
