"""Every package.xml is a valid format-3 manifest declaring the ROS packages its code imports."""

from __future__ import annotations

import ast
import sys
from pathlib import Path

import pytest

catkin_pkg = pytest.importorskip("catkin_pkg.package")

REPO = Path(__file__).resolve().parents[1]
PYTHON_PACKAGES = ("shiproute_core", "shiproute_weather", "shiproute_planner",
                   "shiproute_ais_replay", "shiproute_bringup", "shiproute_display")


def _ros_packages_installed() -> set[str]:
    """Names of ROS packages installed in this prefix (``share/<name>/package.xml``)."""
    share = Path(sys.prefix, "share")
    return {p.parent.name for p in share.glob("*/package.xml")}


def _imported_top_modules(package_dir: Path) -> set[str]:
    """Top-level module names imported anywhere in a package's Python sources."""
    names: set[str] = set()
    for path in package_dir.rglob("*.py"):
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                names.update(alias.name.split(".")[0] for alias in node.names)
            elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                names.add(node.module.split(".")[0])
    return names


@pytest.mark.parametrize("name", ["shiproute_msgs", "foxglove_msgs", *PYTHON_PACKAGES])
def test_manifest_is_valid_format_3(name: str) -> None:
    """catkin_pkg parses and validates the manifest; build type matches the package kind."""
    pkg = catkin_pkg.parse_package(str(REPO / "src" / name / "package.xml"))
    pkg.validate()
    assert pkg.package_format == 3 and pkg.name == name
    expected = "ament_cmake" if name in ("shiproute_msgs", "foxglove_msgs") else "ament_python"
    assert pkg.get_build_type() == expected


@pytest.mark.parametrize("name", PYTHON_PACKAGES)
def test_imported_ros_packages_are_declared(name: str) -> None:
    """Each ROS package (or sibling shiproute package) the code imports is an exec dependency."""
    pkg = catkin_pkg.parse_package(str(REPO / "src" / name / "package.xml"))
    declared = {d.name for d in pkg.exec_depends}
    ros = _ros_packages_installed() | {"shiproute_msgs", "foxglove_msgs", *PYTHON_PACKAGES}
    imported = _imported_top_modules(REPO / "src" / name / name) & ros
    missing = sorted(imported - declared - {name})
    assert not missing, f"src/{name}/package.xml lacks <exec_depend> for {missing}"
