"""Child processes for ROS tests and bringup: own process group, captured lines, clean shutdown.

Used by `shiproute bringup` and by the ROS tests of every package (no rclpy import here):

    from shiproute_bringup.rosproc import RosProcess, random_domain_id, wait_until
    dom = random_domain_id()
    with RosProcess.python("import rclpy; ...", domain_id=dom, name="talker") as talker:
        talker.wait_for_line(r"ready", timeout_s=10)
        ...
    # leaving the block: SIGINT, then SIGTERM, then SIGKILL to the whole process group
"""

from __future__ import annotations

import ctypes
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from pathlib import Path
from typing import IO, TypeVar

from shiproute_bringup.errors import ProcessTimeoutError

T = TypeVar("T")

DEFAULT_STOP_DEADLINES_S = (5.0, 3.0, 2.0)  # after SIGINT, after SIGTERM, after SIGKILL


_PR_SET_PDEATHSIG = 1
_LIBC = ctypes.CDLL(None, use_errno=True) if sys.platform.startswith("linux") else None


def _die_with_parent() -> None:
    """Child-side: receive SIGTERM when the parent thread exits (Linux prctl)."""
    if _LIBC is not None:
        _LIBC.prctl(_PR_SET_PDEATHSIG, signal.SIGTERM)


MAX_DOMAIN_ID = 101  # the highest id safe with the default Fast DDS port mapping
# the other range Fast DDS's port mapping leaves clear of Linux's ephemeral ports (ROS 2
# "The ROS_DOMAIN_ID" concept page): benchmarks draw from it, so a bench run beside the
# tests never shares a domain with one of them
BENCH_DOMAIN_IDS = range(215, 233)


def random_domain_id(rng: random.Random | None = None) -> int:
    """A ROS_DOMAIN_ID in 0..101; under pytest-xdist, from this worker's own residue class
    (worker i of n draws ids = i mod n), so parallel test workers never share a domain."""
    worker = os.environ.get("PYTEST_XDIST_WORKER", "")
    workers = int(os.environ.get("PYTEST_XDIST_WORKER_COUNT", "1") or 1)
    index = int(worker[2:]) if worker.startswith("gw") and worker[2:].isdigit() else 0
    if workers <= 1 or index >= workers:
        return (rng or random.SystemRandom()).randint(0, MAX_DOMAIN_ID)
    choices = range(index, MAX_DOMAIN_ID + 1, workers)
    return (rng or random.SystemRandom()).choice(choices)


def random_bench_domain_id(rng: random.Random | None = None) -> int:
    """A ROS_DOMAIN_ID for a benchmark's nodes, in 215..232: never one the tests draw."""
    return (rng or random.SystemRandom()).choice(BENCH_DOMAIN_IDS)


def ros_env(domain_id: int, extra: Mapping[str, str] | None = None) -> dict[str, str]:
    """This process's environment with the domain id, LOCALHOST discovery and unbuffered output."""
    env = dict(os.environ)
    env["ROS_DOMAIN_ID"] = str(domain_id)
    env.setdefault("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")
    env["PYTHONUNBUFFERED"] = "1"
    env.setdefault("RCUTILS_COLORIZED_OUTPUT", "0")
    if extra:
        env.update(extra)
    return env


def wait_until(predicate: Callable[[], T], timeout_s: float, interval_s: float = 0.05,
               what: str = "condition") -> T:
    """Poll ``predicate`` until it returns a truthy value (returned) or the deadline passes."""
    deadline = time.monotonic() + timeout_s
    while True:
        value = predicate()
        if value:
            return value
        if time.monotonic() >= deadline:
            raise ProcessTimeoutError(f"{what} not reached within {timeout_s:.1f} s")
        time.sleep(interval_s)


def console_script(name: str) -> str:
    """Path of a console script of this venv (next to the running interpreter), else on PATH."""
    candidate = Path(sys.executable).parent / name
    if candidate.is_file():
        return str(candidate)
    found = shutil.which(name)
    if found is None:
        raise FileNotFoundError(f"console script '{name}' not found next to {sys.executable} "
                                "or on PATH (is its package installed?)")
    return found


def signal_group(pgid: int, sig: int) -> bool:
    """Send ``sig`` to a process group; False when the group no longer exists."""
    try:
        os.killpg(pgid, sig)
        return True
    except ProcessLookupError:
        return False


def group_alive(pgid: int) -> bool:
    """True while any process of the group exists (zombies included until reaped)."""
    try:
        os.killpg(pgid, 0)
        return True
    except ProcessLookupError:
        return False
    except PermissionError:
        return True


class RosProcess:
    """One child process in its own process group with its output captured line by line."""

    def __init__(self, argv: Sequence[str], *, domain_id: int | None = None,
                 env: Mapping[str, str] | None = None, name: str = "",
                 cwd: str | os.PathLike[str] | None = None,
                 on_line: Callable[[str, str], None] | None = None,
                 merge_stderr: bool = True, die_with_parent: bool = False) -> None:
        """Start ``argv``; ``on_line(stream, line)`` is called from reader threads for each line.

        ``die_with_parent`` asks Linux to SIGTERM the child if this process dies (even SIGKILL).
        """
        self.argv = list(argv)
        self.name = name or Path(self.argv[0]).name
        self.domain_id = domain_id
        if domain_id is not None:
            full_env = ros_env(domain_id, env)
        else:
            full_env = {**os.environ, **(env or {})}
        self._lines: list[str] = []
        self._cond = threading.Condition()
        self._on_line = on_line
        self.proc = subprocess.Popen(
            self.argv, env=full_env, cwd=cwd, stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT if merge_stderr else subprocess.PIPE,
            start_new_session=True, text=True, bufsize=1, errors="replace",
            preexec_fn=_die_with_parent if die_with_parent else None)
        self.pgid = self.proc.pid  # start_new_session: the child leads its own group
        self._readers = [self._start_reader(self.proc.stdout, "stdout")]
        if not merge_stderr:
            self._readers.append(self._start_reader(self.proc.stderr, "stderr"))

    @classmethod
    def python(cls, code: str, *args: str, **kwargs: object) -> RosProcess:
        """Run a Python snippet with this interpreter (``sys.argv[1:]`` = ``args``)."""
        return cls([sys.executable, "-u", "-c", code, *args], **kwargs)  # type: ignore[arg-type]

    @classmethod
    def script(cls, script_name: str, *args: str, **kwargs: object) -> RosProcess:
        """Run a console script of this venv, e.g. ``shiproute_weather_node --ros-args ...``."""
        return cls([console_script(script_name), *args], **kwargs)  # type: ignore[arg-type]

    def _start_reader(self, stream: IO[str] | None, label: str) -> threading.Thread:
        def pump() -> None:
            assert stream is not None
            for raw in stream:
                line = raw.rstrip("\n")
                with self._cond:
                    self._lines.append(line)
                    self._cond.notify_all()
                if self._on_line is not None:
                    self._on_line(label, line)
            with self._cond:
                self._cond.notify_all()

        thread = threading.Thread(target=pump, name=f"rosproc-{self.name}-{label}", daemon=True)
        thread.start()
        return thread

    @property
    def lines(self) -> list[str]:
        """Copy of all output lines so far."""
        with self._cond:
            return list(self._lines)

    @property
    def output(self) -> str:
        """All output so far as one string."""
        return "\n".join(self.lines)

    def running(self) -> bool:
        """True while the main child has not exited."""
        return self.proc.poll() is None

    def wait_for_line(self, pattern: str, timeout_s: float, start: int = 0) -> re.Match[str]:
        """First output line (from index ``start``) matching ``pattern``; fails early on exit."""
        regex = re.compile(pattern)
        deadline = time.monotonic() + timeout_s
        index = start
        with self._cond:
            while True:
                while index < len(self._lines):
                    match = regex.search(self._lines[index])
                    index += 1
                    if match:
                        return match
                remaining = deadline - time.monotonic()
                if remaining <= 0:
                    raise ProcessTimeoutError(
                        f"{self.name}: no line matching {pattern!r} within {timeout_s:.1f} s; "
                        f"output:\n{self._tail()}")
                if self.proc.poll() is not None and not any(t.is_alive() for t in self._readers):
                    raise ProcessTimeoutError(
                        f"{self.name} exited with {self.proc.returncode} before printing "
                        f"{pattern!r}; output:\n{self._tail()}")
                self._cond.wait(min(remaining, 0.1))

    def _tail(self, n: int = 40) -> str:
        return "\n".join(self._lines[-n:])

    def wait(self, timeout_s: float) -> int:
        """Wait for the child to exit by itself; returns its exit code."""
        try:
            code = self.proc.wait(timeout=timeout_s)
        except subprocess.TimeoutExpired as exc:
            raise ProcessTimeoutError(f"{self.name} still running after {timeout_s:.1f} s; "
                                      f"output:\n{self._tail()}") from exc
        self._join_readers(2.0)
        return code

    def stop(self, deadlines_s: Iterable[float] = DEFAULT_STOP_DEADLINES_S) -> int:
        """SIGINT, then SIGTERM, then SIGKILL to the process group, each after its deadline.

        Returns the main child's exit code. The whole group is gone (or killed) on return.
        """
        code = stop_group(self.proc, self.pgid, tuple(deadlines_s))
        self._join_readers(2.0)
        return code

    def _join_readers(self, timeout_s: float) -> None:
        for thread in self._readers:
            thread.join(timeout_s)

    def __enter__(self) -> RosProcess:
        return self

    def __exit__(self, *exc: object) -> None:
        self.stop()


def stop_group(proc: subprocess.Popen[str], pgid: int,
               deadlines_s: Sequence[float] = DEFAULT_STOP_DEADLINES_S) -> int:
    """Escalate SIGINT -> SIGTERM -> SIGKILL on group ``pgid`` until ``proc`` and group are gone."""
    for sig, deadline in zip((signal.SIGINT, signal.SIGTERM, signal.SIGKILL), deadlines_s,
                             strict=False):
        if proc.poll() is not None and not group_alive(pgid):
            break
        signal_group(pgid, sig)
        end = time.monotonic() + deadline
        while time.monotonic() < end:
            if proc.poll() is not None and not group_alive(pgid):
                break
            time.sleep(0.02)
    if proc.poll() is None:
        signal_group(pgid, signal.SIGKILL)
        proc.wait()
    return proc.returncode if proc.returncode is not None else proc.wait()
