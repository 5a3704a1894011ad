"""Watch a directory for new forecast files; a file counts once its size stopped changing."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

FORECAST_SUFFIXES = (".nc", ".nc4", ".cdf", ".grib", ".grib2", ".grb", ".grb2", ".grib1")


def is_forecast_file(path: Path) -> bool:
    """Forecast-looking name: known suffix, not hidden, not a partial download."""
    name = path.name.lower()
    return (not name.startswith(".") and path.suffix.lower() in FORECAST_SUFFIXES
            and not name.endswith((".part", ".tmp", ".partial")))


@dataclass
class DirectoryWatcher:
    """Poll-based watcher with debounce: returns files whose (size, mtime) stayed unchanged
    for `settle_s` seconds and that were not returned before (a rewritten file counts again)."""

    directory: Path
    settle_s: float = 1.0
    _seen: dict[Path, tuple[int, float, float]] = field(default_factory=dict)  # size, mtime, since
    _done: dict[Path, tuple[int, float]] = field(default_factory=dict)

    def poll(self, now_s: float) -> list[Path]:
        """Newly stable forecast files, sorted by name."""
        ready: list[Path] = []
        try:
            entries = [p for p in self.directory.iterdir() if p.is_file() and is_forecast_file(p)]
        except OSError:
            return ready
        present = set()
        for p in entries:
            try:
                st = p.stat()
            except OSError:
                continue
            present.add(p)
            sig = (st.st_size, st.st_mtime)
            if self._done.get(p) == sig:
                continue
            prev = self._seen.get(p)
            if prev is None or (prev[0], prev[1]) != sig:
                self._seen[p] = (sig[0], sig[1], now_s)
                continue
            if st.st_size > 0 and now_s - prev[2] >= self.settle_s:
                ready.append(p)
                self._done[p] = sig
                del self._seen[p]
        for gone in set(self._seen) - present:
            del self._seen[gone]
        return sorted(ready)

    def mark_existing(self) -> list[Path]:
        """Treat the files present now as handled; return the newest group (mtime within 60 s
        of the newest file) so a node can start from the latest cycle already on disk."""
        files = []
        try:
            files = [p for p in self.directory.iterdir() if p.is_file() and is_forecast_file(p)]
        except OSError:
            return []
        stats = {p: p.stat() for p in files}
        for p, st in stats.items():
            self._done[p] = (st.st_size, st.st_mtime)
        if not stats:
            return []
        newest = max(st.st_mtime for st in stats.values())
        return sorted(p for p, st in stats.items() if newest - st.st_mtime <= 60.0)
