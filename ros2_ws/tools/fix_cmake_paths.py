"""Rewrite build-machine paths baked into the ROS wheels' exported CMake files.

Several ``ros-*-msgs`` wheels export CMake targets whose include directories point at the wheel
build host (``/opt/python/cp311-cp311/...``); CMake refuses to configure a package that depends on
them until those paths name this interpreter's Python and numpy include directories.
Usage: ``python fix_cmake_paths.py <venv>`` (run with the venv's python; idempotent).
"""

from __future__ import annotations

import re
import sys
import sysconfig
from pathlib import Path

import numpy

PY_INCLUDE_RE = re.compile(r"/opt/python/cp3\d+-cp3\d+/include/python3\.\d+")
NUMPY_INCLUDE_RE = re.compile(
    r"/opt/python/cp3\d+-cp3\d+/lib/python3\.\d+/site-packages/numpy/_core/include")


def fix_file(path: Path, py_include: str, numpy_include: str) -> bool:
    """Rewrite one CMake file in place; return True when it changed."""
    text = path.read_text(encoding="utf-8")
    new = NUMPY_INCLUDE_RE.sub(numpy_include, text)
    new = PY_INCLUDE_RE.sub(py_include, new)
    if new == text:
        return False
    path.write_text(new, encoding="utf-8")
    return True


def main(argv: list[str]) -> int:
    """Fix every ``*.cmake`` under ``<venv>/share``; print how many files changed."""
    if len(argv) != 1:
        print("usage: fix_cmake_paths.py <venv>", file=sys.stderr)
        return 2
    share = Path(argv[0]) / "share"
    py_include = sysconfig.get_paths()["include"]
    numpy_include = numpy.get_include()
    if not Path(py_include, "Python.h").is_file():
        print(f"fix_cmake_paths: no Python.h in {py_include} (install python3-dev)",
              file=sys.stderr)
        return 1
    changed = 0
    for path in share.rglob("*.cmake"):
        if "/opt/python/" in path.read_text(encoding="utf-8", errors="replace"):
            changed += fix_file(path, py_include, numpy_include)
    print(f"fix_cmake_paths: {changed} file(s) rewritten")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
