"""Content keys of fleet inputs: the code version, each forecast and each voyage, so a re-run
can tell an output made from the same inputs (skip it) from one made from others (re-plan)."""

from __future__ import annotations

import dataclasses
import functools
import hashlib
import json
import os
from pathlib import Path

from ..plan_request import PlanRequest

_CHUNK = 1 << 20


# sources that do not make plans or their files: command lines, benchmarks, the ROS shells,
# and the fleet's client side (reading voyages, running the batch, the summary)
_NOT_PLANNING = {"cli", "bench", "node.py", "convert.py", "runner.py", "progress.py",
                 "summary.py", "example.py", "voyages.py", "plugin.py", "test"}


@functools.cache
def code_version() -> str:
    """Hash of the planner's and the weather package's sources and bundled data files that
    make plans and their files: any change to them changes it."""
    import shiproute_planner
    import shiproute_weather

    h = hashlib.sha256()
    for pkg in (shiproute_planner, shiproute_weather):
        if pkg.__file__ is None:  # a namespace package: no sources of its own to hash
            raise RuntimeError(f"{pkg.__name__} is not installed as a regular package")
        root = Path(pkg.__file__).parent
        files = sorted(p for p in root.rglob("*")
                       if p.is_file() and p.suffix in (".py", ".yaml", ".json", ".nc")
                       and "__pycache__" not in p.parts
                       and not _NOT_PLANNING.intersection(p.relative_to(root).parts))
        for p in files:
            h.update(str(p.relative_to(root.parent)).encode())
            h.update(_file_digest(p).encode())
    return h.hexdigest()[:16]


@functools.cache
def _file_digest_cached(path: str, size: int, mtime_ns: int) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        while block := fh.read(_CHUNK):
            h.update(block)
    return h.hexdigest()


def _file_digest(p: Path) -> str:
    """SHA-256 of a file's bytes (cached per process by path, size and modification time)."""
    st = p.stat()
    return _file_digest_cached(str(p.resolve()), st.st_size, st.st_mtime_ns)


def forecast_files(spec: str) -> list[Path]:
    """The files a forecast spec names: 'a.grib2+b.nc' (one cycle in several files), one
    file, or a bundled scenario (its NetCDF, built on first use)."""
    parts = [s for s in spec.split("+") if s]
    if all(Path(s).is_file() for s in parts):
        return [Path(s).resolve() for s in parts]
    from shiproute_weather.scenarios.catalogue import scenario_names, scenario_path

    if spec in scenario_names():
        return [scenario_path(spec)]
    from ..errors import InvalidVoyageError

    raise InvalidVoyageError(
        f"forecast {spec!r} is neither a file (or files joined with '+') nor a bundled "
        f"scenario ({', '.join(scenario_names())})")


def forecast_key(spec: str | None) -> str:
    """Hash of a forecast's file contents ('calm' for no forecast)."""
    if spec is None:
        return "calm"
    h = hashlib.sha256()
    for p in forecast_files(spec):
        h.update(_file_digest(p).encode())
    return h.hexdigest()[:16]


def ship_key(ship: str) -> str:
    """A ship file's content hash (bundled ships are covered by the code version)."""
    p = Path(ship)
    return _file_digest(p)[:16] if p.is_file() else ship


def voyage_key(request: PlanRequest, forecast_key_: str, code: str | None = None,
               extra: str = "") -> str:
    """Hash of everything that decides a voyage's plan: request, ship file, forecast, code."""
    data = dataclasses.asdict(request)
    data["ship_file"] = ship_key(request.ship)
    payload = json.dumps([data, forecast_key_, code or code_version(), extra], sort_keys=True,
                         default=str)
    return hashlib.sha256(payload.encode()).hexdigest()[:20]


def describe_files(spec: str | None) -> str:
    """Short human description of a forecast spec for summaries."""
    if spec is None:
        return "calm water"
    return " + ".join(os.path.basename(str(p)) for p in forecast_files(spec))
