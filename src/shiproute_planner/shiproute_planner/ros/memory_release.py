"""Give back, after each plan, the memory the planner node does not keep between plans.

Two kinds go back (Linux; elsewhere nothing happens):
- freed heap: glibc keeps freed blocks of a plan's arrays and of a cycle's slice buffers
  (`process_tuning.return_freed_memory`);
- pages of read-only file maps (the land raster, its sea-distance raster, the prepared depth
  grids, all `.npy` in the shiproute data directory): a plan's land and depth scans touch
  them, and every touched page stays in the process's resident set although it is clean and
  can be read again from the page cache at once. `madvise(MADV_DONTNEED)` drops them from
  this process only (the page cache and other processes keep them).
"""

from __future__ import annotations

import ctypes
import mmap
import os
from collections.abc import Iterator
from dataclasses import dataclass

from ..geo.datadir import data_dir
from . import process_tuning as tuning

#: the file maps whose pages are dropped: the prepared rasters and grids
MAPPED_SUFFIXES = (".npy",)


@dataclass(frozen=True)
class Released:
    """What one release returned and what the process holds after it [MiB]."""

    file_pages_mb: float
    resident_mb: float
    peak_mb: float

    def text(self) -> str:
        """One log line."""
        return (f"planner memory: {self.resident_mb:.0f} MiB resident, peak "
                f"{self.peak_mb:.0f} MiB ({self.file_pages_mb:.0f} MiB of file-mapped raster "
                "pages handed back)")


def read_only_file_maps(directory: str, maps_path: str = "/proc/self/maps"
                        ) -> Iterator[tuple[int, int]]:
    """(start, end) addresses of this process's read-only maps of `MAPPED_SUFFIXES` files
    under `directory` (none where /proc is missing)."""
    prefix = os.path.join(os.path.realpath(directory), "")
    try:
        with open(maps_path) as f:
            lines = f.readlines()
    except OSError:
        return
    for line in lines:
        parts = line.split(maxsplit=5)
        if len(parts) < 6 or "w" in parts[1]:
            continue
        path = parts[5].strip()
        if path.startswith(prefix) and path.endswith(MAPPED_SUFFIXES):
            start, end = (int(x, 16) for x in parts[0].split("-"))
            yield start, end


def resident_kib(start: int, end: int, smaps_path: str = "/proc/self/smaps") -> int:
    """Resident KiB of the map starting at `start` (0 when it is not found)."""
    head = f"{start:x}-{end:x} "
    try:
        with open(smaps_path) as f:
            found = False
            for line in f:
                if line.startswith(head):
                    found = True
                elif found and line.startswith("Rss:"):
                    return int(line.split()[1])
    except (OSError, ValueError):
        pass
    return 0


def drop_file_pages(directory: str) -> float:
    """Drop the resident pages of the read-only raster maps under `directory`; returns the
    MiB that were resident in them."""
    try:
        madvise = ctypes.CDLL("libc.so.6", use_errno=True).madvise
    except (OSError, AttributeError):
        return 0.0
    madvise.argtypes = (ctypes.c_void_p, ctypes.c_size_t, ctypes.c_int)
    dropped_kib = 0
    for start, end in read_only_file_maps(directory):
        kib = resident_kib(start, end)
        if kib and madvise(start, end - start, mmap.MADV_DONTNEED) == 0:
            dropped_kib += kib
    return dropped_kib / 1024.0


def release_after_plan(collect: bool, data_directory: str | None = None) -> Released:
    """After a plan: drop the raster pages it touched (maps under `data_directory`, default
    the shiproute data directory) and return freed heap memory. With `collect` (a new cycle's
    first plan) a full garbage collection runs first, and what the process holds then is left
    out of later collections (`process_tuning.freeze_long_lived`)."""
    file_mb = drop_file_pages(str(data_dir()) if data_directory is None else data_directory)
    tuning.return_freed_memory(collect=collect)
    if collect:
        tuning.freeze_long_lived()  # after the first plan, which loaded all planning needs
    rss, peak = tuning.memory_mb()
    return Released(file_mb, rss, peak)
