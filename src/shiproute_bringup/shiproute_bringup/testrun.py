"""Run the test suite (pytest from the repo root with the repo config); zero tests is a failure."""

from __future__ import annotations

import importlib.util
import subprocess
import sys

from shiproute_bringup.paths import repo_root

NO_TESTS_COLLECTED = 5
DEFAULT_TIMEOUT_S = 600


def pytest_command(argv: list[str]) -> list[str]:
    """``python -m pytest`` with a per-test timeout (pytest-timeout) unless one is given."""
    cmd = [sys.executable, "-m", "pytest"]
    has_timeout = any(a.startswith("--timeout") for a in argv)
    if importlib.util.find_spec("pytest_timeout") is not None and not has_timeout:
        cmd.append(f"--timeout={DEFAULT_TIMEOUT_S}")
    return cmd + argv


def main(argv: list[str]) -> int:
    """``shiproute test [pytest args]``: exit code of pytest, except 'no tests ran' -> 1."""
    if argv[:1] in (["-h"], ["--help"]) and len(argv) == 1:
        print("usage: shiproute test [pytest args...]\n\n" + (__doc__ or "").strip() +
              "\nExamples: shiproute test -k msgs; shiproute test -m 'not slow'; "
              "shiproute test src/shiproute_planner/test")
        return 0
    root = repo_root()
    code = subprocess.call(pytest_command(argv), cwd=root)
    if code == NO_TESTS_COLLECTED:
        print("shiproute test: no tests ran (pytest exit 5) - treated as failure", file=sys.stderr)
        return 1
    return code
