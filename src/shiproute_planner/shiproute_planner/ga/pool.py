"""Seed pool: best known route per (departure port, arrival port, month), as JSON on disk.

A seed is stored as its track (node positions) and per-leg RPMs, not as genes, so it can seed
a problem with a different number of stages or a departure shifted along the route. The
better of the planner's result and the stored seed is kept (thesis sec. 5.2, fig. 23); the
file is replaced atomically so a crash never leaves a half-written pool, and every offer merges
under an exclusive lock on `seed_pool.json.lock` (read, compare, write, rename), so processes
sharing one pool (fleet workers, several nodes) never lose each other's seeds.
"""

from __future__ import annotations

import contextlib
import fcntl
import json
import os
import threading
import time
import uuid
from collections.abc import Iterator
from dataclasses import asdict, dataclass
from pathlib import Path

from ..errors import SeedPoolError
from .ranking import is_better

POOL_FILE = "seed_pool.json"


@dataclass(frozen=True)
class Seed:
    """A stored route: node positions, RPM per leg, and how good it was when stored."""

    key: str
    lon_deg: tuple[float, ...]
    lat_deg: tuple[float, ...]
    rpm: tuple[float, ...]
    objective: str
    objective_value: float
    violation: float
    fuel_t: float
    source: str = ""
    stored_at: float = 0.0
    genes: tuple[float, ...] = ()  # heading/RPM genes (used as-is when the stage count fits)


def pool_key(dep: str, arr: str, month: int) -> str:
    """Key of a seed: ports (UN/LOCODE or rounded position) and departure month 1..12."""
    return f"{dep.upper()}->{arr.upper()}@{month:02d}"


class SeedPool:
    """Seeds in `directory`/seed_pool.json; safe to share between runs and restarts."""

    def __init__(self, directory: str | Path) -> None:
        self.path = Path(directory) / POOL_FILE

    def _read(self) -> dict[str, dict]:
        if not self.path.is_file():
            return {}
        try:
            data = json.loads(self.path.read_text())
        except (OSError, json.JSONDecodeError) as exc:
            raise SeedPoolError(f"seed pool {self.path} is unreadable: {exc}") from exc
        if not isinstance(data, dict) or not isinstance(data.get("seeds", {}), dict):
            raise SeedPoolError(f"seed pool {self.path} has no 'seeds' object")
        return data.get("seeds", {})

    def __len__(self) -> int:
        """Number of stored seeds (port pairs x months)."""
        return len(self._read())

    def get(self, key: str) -> Seed | None:
        """The stored seed for `key`, or None."""
        raw = self._read().get(key)
        if raw is None:
            return None
        try:
            return Seed(**{**raw, "lon_deg": tuple(raw["lon_deg"]),
                           "lat_deg": tuple(raw["lat_deg"]), "rpm": tuple(raw["rpm"]),
                           "genes": tuple(raw.get("genes", ()))})
        except (TypeError, KeyError) as exc:
            raise SeedPoolError(f"seed {key!r} in {self.path} is malformed: {exc}") from exc

    @contextlib.contextmanager
    def _locked(self) -> Iterator[None]:
        """Exclusive lock of the pool across processes (flock) and threads of one process."""
        self.path.parent.mkdir(parents=True, exist_ok=True)
        lock_path = self.path.with_name(self.path.name + ".lock")
        with _THREAD_LOCK:
            try:
                fd = os.open(lock_path, os.O_RDWR | os.O_CREAT, 0o644)
            except OSError as exc:
                raise SeedPoolError(f"cannot lock seed pool {self.path}: {exc}") from exc
            try:
                fcntl.flock(fd, fcntl.LOCK_EX)
                yield
            finally:
                os.close(fd)  # releases the flock

    def offer(self, seed: Seed) -> bool:
        """Store `seed` if the pool has none for its key or it beats the stored one."""
        with self._locked():
            seeds = self._read()
            old = seeds.get(seed.key)
            if old is not None and old.get("objective") == seed.objective and not is_better(
                seed.violation, seed.objective_value, old["violation"], old["objective_value"]
            ):
                return False
            seeds[seed.key] = {**asdict(seed), "stored_at": time.time()}
            tmp = self.path.with_suffix(f".{os.getpid()}.{uuid.uuid4().hex[:8]}.tmp")
            try:
                tmp.write_text(json.dumps({"version": 1, "seeds": seeds}, indent=1))
                os.replace(tmp, self.path)
            except OSError as exc:
                tmp.unlink(missing_ok=True)
                raise SeedPoolError(f"cannot write seed pool {self.path}: {exc}") from exc
            return True


_THREAD_LOCK = threading.Lock()  # flock is per open file: threads of one process queue here
