"""`shiproute bringup` starts nodes with params files, forwards logs, and leaves no orphans."""

from __future__ import annotations

import signal
import sys
import time
from pathlib import Path

import psutil
import pytest
import yaml
from shiproute_bringup.bringup_config import load_bringup
from shiproute_bringup.errors import BringupFileError
from shiproute_bringup.paths import default_params_file
from shiproute_bringup.rosproc import RosProcess, console_script, random_domain_id, wait_until

# A real rclpy node: declares a float and a string parameter and prints them from the params file.
PARAM_NODE = """
import sys, rclpy
from rclpy.node import Node
rclpy.init(args=sys.argv)
node = Node("placeholder")
speed = node.declare_parameter("speed_kn", 0.0).value
label = node.declare_parameter("label", "").value
print(f"node={node.get_name()} speed_kn={speed!r} label={label}", flush=True)
try:
    rclpy.spin(node)
except BaseException:
    pass
"""

# A stubborn process: ignores SIGINT, has a grandchild in its group, runs until killed.
STUBBORN = """
import signal, subprocess, sys, time
signal.signal(signal.SIGINT, signal.SIG_IGN)
child = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(600)"])
print(f"grandchild={child.pid}", flush=True)
while True:
    time.sleep(0.1)
"""

QUICK_EXIT = "import sys; print('done', flush=True); sys.exit(3)"


def _write(tmp_path: Path, nodes: list[dict[str, object]], **top: object) -> Path:
    path = tmp_path / "bringup.yaml"
    path.write_text(yaml.safe_dump({**top, "nodes": nodes}))
    return path


def _py_node(name: str, code: str, **extra: object) -> dict[str, object]:
    return {"name": name, "executable": sys.executable, "args": ["-c", code], **extra}


def _start_bringup(path: Path, *extra: str) -> RosProcess:
    return RosProcess.script("shiproute", "bringup", str(path), *extra,
                             domain_id=random_domain_id(), name="bringup")


def _alive(pids: list[int]) -> list[int]:
    out = []
    for pid in pids:
        try:
            if psutil.Process(pid).status() != psutil.STATUS_ZOMBIE:
                out.append(pid)
        except psutil.NoSuchProcess:
            pass
    return out


@pytest.mark.ros
def test_sigterm_stops_all_nodes_and_grandchildren(tmp_path: Path) -> None:
    """Params reach the node; SIGTERM to bringup ends every descendant (SIGINT ignored ones too)."""
    path = _write(tmp_path, [
        _py_node("talker", PARAM_NODE, parameters={"speed_kn": 14.5, "label": "${MY_LABEL}"},
                 env={"MY_LABEL": "from-env"}),
        _py_node("stubborn", STUBBORN),
    ])
    with _start_bringup(path) as bringup:
        bringup.wait_for_line(r"\[talker\s*\] node=talker speed_kn=14.5 label=from-env", 20)
        grandchild = int(bringup.wait_for_line(r"\[stubborn\s*\] grandchild=(\d+)", 20).group(1))
        tree = [p.pid for p in psutil.Process(bringup.proc.pid).children(recursive=True)]
        assert grandchild in tree and len(tree) >= 3
        bringup.proc.send_signal(signal.SIGTERM)
        code = bringup.wait(timeout_s=20)  # SIGINT (5 s) then SIGTERM for the stubborn one
    assert code == 0
    wait_until(lambda: not _alive(tree), 5, what="all node processes gone")
    assert "SIGTERM to stubborn" in bringup.output


@pytest.mark.ros
def test_required_node_exit_ends_bringup(tmp_path: Path) -> None:
    """When a required node exits, the others are stopped and its failure is the exit status."""
    path = _write(tmp_path, [
        _py_node("worker", "import time; time.sleep(600)"),
        _py_node("oneshot", QUICK_EXIT, required=True),
    ])
    t0 = time.monotonic()
    with _start_bringup(path) as bringup:
        code = bringup.wait(timeout_s=20)
    assert code == 1
    assert time.monotonic() - t0 < 15
    assert "required node oneshot exited with 3" in bringup.output


@pytest.mark.ros
def test_duration_limit(tmp_path: Path) -> None:
    """--duration stops everything after the given time with exit 0."""
    path = _write(tmp_path, [_py_node("sleeper", "import time; time.sleep(600)")])
    t0 = time.monotonic()
    with _start_bringup(path, "--duration", "1.0") as bringup:
        code = bringup.wait(timeout_s=20)
    elapsed = time.monotonic() - t0
    assert code == 0 and 1.0 <= elapsed < 12
    assert "duration 1 s reached" in bringup.output


def test_bad_files_are_rejected_with_reason(tmp_path: Path) -> None:
    """Missing file, missing executable, unknown keys and duplicates are named in the error."""
    with pytest.raises(BringupFileError, match="cannot read"):
        load_bringup(tmp_path / "nope.yaml")
    with pytest.raises(BringupFileError, match="'executable'"):
        load_bringup(_write(tmp_path, [{"name": "a"}]))
    with pytest.raises(BringupFileError, match="not a console script"):
        load_bringup(_write(tmp_path, [{"name": "a", "executable": "no_such_script_xyz"}]))
    with pytest.raises(BringupFileError, match="unknown keys"):
        load_bringup(_write(tmp_path, [_py_node("a", "pass", paramz={})]))
    with pytest.raises(BringupFileError, match="duplicate"):
        load_bringup(_write(tmp_path, [_py_node("a", "pass"), _py_node("a", "pass")]))
    res = RosProcess.script("shiproute", "bringup", str(tmp_path / "nope.yaml"), name="bad")
    assert res.wait(20) == 2 and "cannot read" in res.output


def test_default_demo_file_is_valid() -> None:
    """The bundled ros2_ws/params/demo.yaml lists the suite's nodes and the bridge display."""
    nodes = load_bringup(default_params_file())
    assert [Path(n.executable).name for n in nodes] == [
        "shiproute_weather_node", "shiproute_replay_node", "shiproute_planner_node",
        "shiproute_display_node"]
    for node in nodes:
        argv = node.argv(Path("/tmp/p.yaml"))
        assert argv[argv.index("--ros-args") + 1:][:4] == [
            "--params-file", "/tmp/p.yaml", "-r", f"__node:={node.name}"]


def test_console_script_lookup() -> None:
    """console_script finds venv scripts and names the missing ones."""
    assert Path(console_script("shiproute")).is_file()
    with pytest.raises(FileNotFoundError, match="no_such_script_xyz"):
        console_script("no_such_script_xyz")
