"""Run the test suite (pytest from the repo root with the repo config); zero tests is a failure.

The whole suite (no test paths given) runs on every core with pytest-xdist, one test file per
worker at a time (`--dist loadfile`, so a file's module-scoped ROS nodes start once); each
worker draws ROS domain ids from its own share of the range (`rosproc.random_domain_id`).
"""

from __future__ import annotations

import importlib.util
import subprocess
import sys

from shiproute_bringup.paths import repo_root

NO_TESTS_COLLECTED = 5
DEFAULT_TIMEOUT_S = 600
SLOWEST_SHOWN = 15  # the suite's slowest tests, printed so a CI log shows where time goes


def _selects_paths(argv: list[str]) -> bool:
    """True when the arguments name test files or folders (a developer's focused run)."""
    skip_next = False
    for arg in argv:
        if skip_next:
            skip_next = False
            continue
        if arg in ("-k", "-m", "-p", "-n", "--timeout", "--dist", "--durations", "-c",
                   "--rootdir", "--basetemp"):
            skip_next = True
            continue
        if not arg.startswith("-"):
            return True
    return False


def _parallel_args(argv: list[str]) -> list[str]:
    """`-n auto --dist loadfile` for a whole-suite run when xdist is installed and not set."""
    if importlib.util.find_spec("xdist") is None or _selects_paths(argv):
        return []
    if any(a == "-n" or a.startswith(("-n", "--numprocesses", "--dist")) for a in argv):
        return []
    if "no:xdist" in argv:
        return []
    return ["-n", "auto", "--dist", "loadfile", f"--durations={SLOWEST_SHOWN}"]


def pytest_command(argv: list[str]) -> list[str]:
    """``python -m pytest`` with a per-test timeout (pytest-timeout) unless one is given."""
    cmd = [sys.executable, "-m", "pytest"]
    has_timeout = any(a.startswith("--timeout") for a in argv)
    if importlib.util.find_spec("pytest_timeout") is not None and not has_timeout:
        cmd.append(f"--timeout={DEFAULT_TIMEOUT_S}")
    return cmd + _parallel_args(argv) + argv


def main(argv: list[str]) -> int:
    """``shiproute test [pytest args]``: exit code of pytest, except 'no tests ran' -> 1."""
    if argv[:1] in (["-h"], ["--help"]) and len(argv) == 1:
        print("usage: shiproute test [pytest args...]\n\n" + (__doc__ or "").strip() +
              "\nExamples: shiproute test -k msgs; shiproute test -m 'not slow'; "
              "shiproute test src/shiproute_planner/test; shiproute test -p no:xdist")
        return 0
    root = repo_root()
    code = subprocess.call(pytest_command(argv), cwd=root)
    if code == NO_TESTS_COLLECTED:
        print("shiproute test: no tests ran (pytest exit 5) - treated as failure", file=sys.stderr)
        return 1
    return code
