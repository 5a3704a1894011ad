"""Start the nodes listed in a bringup YAML as supervised processes (our `ros2 launch`).

File format (``ros2_ws/params/demo.yaml`` is the bundled one)::

    common_parameters: {use_sim_time: true}   # merged under every node's parameters
    nodes:
      - name: weather                          # ROS node name (-r __node:=weather), log prefix
        executable: shiproute_weather_node     # console script of the venv (or a path)
        parameters: {forecast_dir: "${SHIPROUTE_DATA_DIR}/forecasts"}
        args: []                               # extra arguments before --ros-args
        ros_args: []                           # extra arguments after --ros-args
        env: {RCUTILS_LOGGING_USE_STDOUT: "1"} # extra environment
        required: false                        # true: bringup ends when this node exits

``${VAR}`` in string parameters, args and env values expands from the environment, the
node's own ``env`` entries, and ``SHIPROUTE_PARAMS_DIR`` = the YAML file's directory. Each
node gets a ROS params file (``/**: ros__parameters: ...``) written to a temporary directory.
"""

from __future__ import annotations

import argparse
import os
import signal
import sys
import tempfile
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from types import FrameType
from typing import Any

import yaml

from shiproute_bringup.bringup_config import NodeSpec, load_bringup
from shiproute_bringup.errors import BringupError
from shiproute_bringup.paths import default_params_file
from shiproute_bringup.rosproc import RosProcess, group_alive, signal_group

STOP_DEADLINES_S = (5.0, 3.0, 2.0)  # SIGINT -> wait -> SIGTERM -> wait -> SIGKILL -> wait


@dataclass
class Supervisor:
    """Runs node processes, forwards their output with a name prefix, and stops them all."""

    nodes: list[NodeSpec]
    params_dir: Path
    out: Any = sys.stdout
    procs: dict[str, RosProcess] = field(default_factory=dict)
    _lock: threading.Lock = field(default_factory=threading.Lock)

    def _line_sink(self, name: str) -> Callable[[str, str], None]:
        """The on_line callback of node `name`: its lines, prefixed, on the shared output."""
        def sink(_stream: str, line: str) -> None:
            self._emit(name, line)
        return sink

    def _emit(self, name: str, line: str) -> None:
        width = max(len(n.name) for n in self.nodes)
        with self._lock:
            self.out.write(f"[{name:<{width}}] {line}\n")
            self.out.flush()

    def say(self, text: str) -> None:
        """A line from the supervisor itself."""
        self._emit("bringup", text)

    def start(self) -> None:
        """Write each node's params file and start it in its own process group."""
        for spec in self.nodes:
            params_file = self.params_dir / f"{spec.name}.params.yaml"
            params_file.write_text(yaml.safe_dump({"/**": {"ros__parameters": spec.parameters}},
                                                  sort_keys=False))
            argv = spec.argv(params_file)
            proc = RosProcess(argv, env=spec.env, name=spec.name, die_with_parent=True,
                              on_line=self._line_sink(spec.name))
            self.procs[spec.name] = proc
            self.say(f"started {spec.name} (pid {proc.proc.pid}): {' '.join(argv)}")

    def exited_required(self) -> NodeSpec | None:
        """The first required node that has exited, if any."""
        for spec in self.nodes:
            if spec.required and not self.procs[spec.name].running():
                return spec
        return None

    def all_exited(self) -> bool:
        """True when every node process has exited."""
        return all(not p.running() for p in self.procs.values())

    def stop_all(self, deadlines_s: tuple[float, ...] = STOP_DEADLINES_S) -> None:
        """Escalate SIGINT -> SIGTERM -> SIGKILL over all process groups together."""
        for sig, deadline in zip((signal.SIGINT, signal.SIGTERM, signal.SIGKILL), deadlines_s,
                                 strict=True):
            alive = [p for p in self.procs.values() if p.running() or group_alive(p.pgid)]
            if not alive:
                break
            if sig != signal.SIGINT:
                self.say(f"{signal.Signals(sig).name} to {', '.join(p.name for p in alive)}")
            for p in alive:
                signal_group(p.pgid, sig)
            end = time.monotonic() + deadline
            while time.monotonic() < end and any(
                    p.running() or group_alive(p.pgid) for p in alive):
                time.sleep(0.02)
        for p in self.procs.values():
            p.stop((0.5, 0.5, 0.5))  # reaps; a no-op for exited groups
            self.say(f"{p.name} exited with {p.proc.returncode}")


def run(nodes: list[NodeSpec], duration_s: float | None) -> int:
    """Supervise until a signal, a required node's exit, all nodes' exit or the duration."""
    stop = threading.Event()
    reason: list[str] = []

    def on_signal(signum: int, _frame: FrameType | None) -> None:
        reason.append(signal.Signals(signum).name)
        stop.set()

    old = {s: signal.signal(s, on_signal) for s in (signal.SIGINT, signal.SIGTERM)}
    code = 0
    with tempfile.TemporaryDirectory(prefix="shiproute-bringup-") as tmp:
        sup = Supervisor(nodes, Path(tmp))
        try:
            sup.start()
            t0 = time.monotonic()
            while not stop.wait(0.1):
                dead = sup.exited_required()
                if dead is not None:
                    rc = sup.procs[dead.name].proc.returncode
                    reason.append(f"required node {dead.name} exited with {rc}")
                    code = 0 if rc == 0 else 1
                    break
                if sup.all_exited():
                    reason.append("all nodes exited")
                    break
                if duration_s is not None and time.monotonic() - t0 >= duration_s:
                    reason.append(f"duration {duration_s:g} s reached")
                    break
            sup.say(f"shutting down ({reason[-1] if reason else 'stop'})")
        finally:
            sup.stop_all()
            for s, handler in old.items():
                signal.signal(s, handler)
    return code


def main(argv: list[str]) -> int:
    """``shiproute bringup [params.yaml] [--duration S]``."""
    parser = argparse.ArgumentParser(prog="shiproute bringup",
                                     description=(__doc__ or "").split("\n\n")[0])
    parser.add_argument("params", nargs="?", type=Path, default=None,
                        help="bringup YAML (default: ros2_ws/params/demo.yaml)")
    parser.add_argument("--duration", type=float, default=None, metavar="S",
                        help="stop all nodes after S seconds")
    parser.add_argument("--dry-run", action="store_true",
                        help="print the command line of each node and exit")
    args = parser.parse_args(argv)
    path = args.params or default_params_file()
    try:
        nodes = load_bringup(path)
    except BringupError as exc:
        print(f"shiproute bringup: {exc}", file=sys.stderr)
        return 2
    if args.dry_run:
        for spec in nodes:
            print(f"{spec.name}: {' '.join(spec.argv(Path(f'<{spec.name}.params.yaml>')))}")
            print(f"  parameters: {spec.parameters}")
        return 0
    os.environ.setdefault("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")
    return run(nodes, args.duration)
