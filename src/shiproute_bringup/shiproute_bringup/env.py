"""Print the environment: Python, rclpy, RMW, ROS distro, message packages, libraries, discovery."""

from __future__ import annotations

import argparse
import importlib
import importlib.metadata as md
import json
import os
import platform
import sys
from pathlib import Path

MESSAGE_PACKAGES = (
    "std_msgs", "builtin_interfaces", "geometry_msgs", "nav_msgs", "sensor_msgs",
    "diagnostic_msgs", "rosgraph_msgs", "shiproute_msgs",
)
LIBRARIES = (
    "numpy", "scipy", "xarray", "pandas", "netCDF4", "h5netcdf", "cfgrib", "eccodes", "pyproj",
    "shapely", "searoute", "numba", "pymoo", "matplotlib", "rosbags", "mcap", "mcap-ros2-support",
    "pyais", "PyYAML", "xmlschema", "psutil", "pytest",
)
SHIPROUTE_PACKAGES = ("shiproute_weather", "shiproute_planner", "shiproute_ais_replay",
                      "shiproute_bringup")


def _dist_version(name: str) -> str | None:
    """Installed version of a distribution, trying the ``ros-`` wheel name for ROS packages."""
    for candidate in (f"ros-{name.replace('_', '-')}", name):
        try:
            return md.version(candidate)
        except md.PackageNotFoundError:
            continue
    return None


def _message_package(name: str) -> dict[str, object]:
    """Version and importability of one interface package."""
    info: dict[str, object] = {"version": _dist_version(name)}
    try:
        module = importlib.import_module(f"{name}.msg")
        info["importable"] = True
        info["path"] = str(Path(module.__file__ or "").parent.parent)
    except Exception as exc:
        info["importable"] = False
        info["error"] = f"{type(exc).__name__}: {exc}"
    if name == "shiproute_msgs" and info["version"] is None and info["importable"]:
        info["version"] = _share_package_version(name)
    return info


def _share_package_version(name: str) -> str | None:
    """Version from ``<prefix>/share/<name>/package.xml`` (packages built into the venv)."""
    xml = Path(sys.prefix, "share", name, "package.xml")
    if not xml.is_file():
        return None
    import xml.etree.ElementTree as ET

    node = ET.parse(xml).getroot().find("version")
    return None if node is None else (node.text or "").strip()


def _rmw_identifier() -> dict[str, object]:
    """The RMW implementation rclpy loads (by initialising a context; no node is created)."""
    try:
        import rclpy
        from rclpy.utilities import get_rmw_implementation_identifier

        return {"identifier": get_rmw_implementation_identifier(),
                "rclpy": _dist_version("rclpy"), "rclpy_path": str(Path(rclpy.__file__).parent)}
    except Exception as exc:
        return {"identifier": None, "error": f"{type(exc).__name__}: {exc}"}


def collect() -> dict[str, object]:
    """Everything `shiproute env` reports, as a JSON-serialisable dict."""
    return {
        "python": {"version": platform.python_version(), "executable": sys.executable,
                   "prefix": sys.prefix},
        "platform": platform.platform(),
        "ros": {
            "distro": os.environ.get("ROS_DISTRO") or _ros_distro_from_wheels(),
            "rmw": _rmw_identifier(),
            "rmw_implementation_env": os.environ.get("RMW_IMPLEMENTATION"),
            "domain_id": int(os.environ.get("ROS_DOMAIN_ID", "0") or 0),
            "automatic_discovery_range": os.environ.get("ROS_AUTOMATIC_DISCOVERY_RANGE",
                                                        "(unset: SUBNET)"),
        },
        "message_packages": {name: _message_package(name) for name in MESSAGE_PACKAGES},
        "libraries": {name: _dist_version(name) for name in LIBRARIES},
        "shiproute_packages": {name: _dist_version(name) for name in SHIPROUTE_PACKAGES},
        "data_dir": os.environ.get("SHIPROUTE_DATA_DIR"),
    }


def _ros_distro_from_wheels() -> str | None:
    """ROS distro from ``share/ros_environment`` if present, else inferred from rclpy 9.x."""
    for path in (Path(sys.prefix, "share", "ros_environment", "environment", "1.ros_distro.sh"),):
        if path.is_file():
            for line in path.read_text().splitlines():
                if "ROS_DISTRO=" in line:
                    return line.split("=", 1)[1].strip().strip("'\"")
    # rclpy 9.x is the Kilted release line; report it with its provenance.
    version = _dist_version("rclpy") or ""
    return "kilted (rclpy 9.x wheels)" if version.startswith("9.") else None


def _print_text(report: dict[str, object]) -> None:
    """Human-readable form of the report."""
    py = report["python"]
    ros = report["ros"]
    assert isinstance(py, dict) and isinstance(ros, dict)
    rmw = ros["rmw"]
    assert isinstance(rmw, dict)
    print(f"python            {py['version']} ({py['executable']})")
    print(f"rclpy             {rmw.get('rclpy')}")
    print(f"rmw               {rmw.get('identifier') or rmw.get('error')}")
    print(f"ros distro        {ros['distro']}")
    print(f"ROS_DOMAIN_ID     {ros['domain_id']}")
    print(f"discovery range   {ros['automatic_discovery_range']}")
    print(f"data dir          {report['data_dir']}")
    print("message packages:")
    packages = report["message_packages"]
    assert isinstance(packages, dict)
    for name, info in packages.items():
        state = "ok" if info["importable"] else f"NOT IMPORTABLE ({info.get('error')})"
        print(f"  {name:<22} {info['version'] or '?':<10} {state}")
    print("libraries:")
    libraries, shiproute = report["libraries"], report["shiproute_packages"]
    assert isinstance(libraries, dict) and isinstance(shiproute, dict)
    for name, version in {**libraries, **shiproute}.items():
        print(f"  {name:<22} {version or 'not installed'}")


def main(argv: list[str]) -> int:
    """``shiproute env [--json]``; exit 1 when rclpy or a message package is unusable."""
    parser = argparse.ArgumentParser(prog="shiproute env", description=__doc__)
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    args = parser.parse_args(argv)
    report = collect()
    if args.json:
        print(json.dumps(report, indent=2))
    else:
        _print_text(report)
    msgs = report["message_packages"]
    assert isinstance(msgs, dict)
    ok = report["ros"]["rmw"].get("identifier") is not None and all(  # type: ignore[index]
        info["importable"] for info in msgs.values())
    return 0 if ok else 1
