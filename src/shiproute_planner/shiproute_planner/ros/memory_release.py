"""Give back, after each plan, the memory the planner node does not keep between plans.

Two kinds go back (Linux; elsewhere nothing happens):
- freed heap: glibc keeps freed blocks of a plan's arrays and of a cycle's slice buffers
  (`process_tuning.return_freed_memory`);
- pages of read-only file maps (the land raster, its sea-distance raster, the prepared depth
  grids, all `.npy` in the shiproute data directory): a plan's land and depth scans touch
  them, and every touched page stays in the process's resident set although it is clean and
  can be read again from the page cache at once. `madvise(MADV_DONTNEED)` drops them from
  this process only (the page cache and other processes keep them);
- pages of LLVM's library (~70 MB touched while the kernels are compiled or loaded), idle
  between plans; only maps without write permission and without a private (relocated) copy
  of any page are dropped, so every dropped page is the file's own and is read back unchanged.
"""

from __future__ import annotations

import ctypes
import mmap
import os
from collections.abc import Callable
from dataclasses import dataclass

from ..geo.datadir import data_dir
from . import process_tuning as tuning

#: the file maps whose pages are dropped: the prepared rasters and grids ...
MAPPED_SUFFIXES = (".npy",)
#: ... and the code and constant pages of LLVM, which compiles the numba kernels (or loads
#: them from numba's cache) before the first plan and is idle after it
COMPILER_LIBRARIES = ("libllvmlite.so",)


@dataclass(frozen=True)
class Released:
    """What one release handed back and what the process holds after it [MiB]."""

    file_pages_mb: float
    resident_mb: float
    peak_mb: float

    def text(self) -> str:
        """One log line."""
        return (f"planner memory: {self.resident_mb:.0f} MiB resident, peak "
                f"{self.peak_mb:.0f} MiB ({self.file_pages_mb:.0f} MiB of file-mapped raster "
                "pages handed back)")


def clean_file_maps(select: Callable[[str], bool], smaps_path: str = "/proc/self/smaps"
                    ) -> list[tuple[int, int, int]]:
    """(start, end, resident KiB) of this process's file maps that `select(path)` accepts,
    are not writable and hold no private copy of a page (Anonymous 0): every resident page is
    the file's own, so dropping it loses nothing (none where /proc is missing)."""
    found: list[tuple[int, int, int]] = []
    current: list[int] | None = None  # start, end, rss, anonymous of an accepted map
    try:
        with open(smaps_path) as f:
            for line in f:
                head = line.split(maxsplit=5)
                if len(head) >= 5 and "-" in head[0] and len(head[1]) == 4:
                    if current is not None and current[3] == 0:
                        found.append((current[0], current[1], current[2]))
                    path = head[5].strip() if len(head) == 6 else ""
                    current = None
                    if "w" not in head[1] and path.startswith("/") and select(path):
                        a, b = (int(x, 16) for x in head[0].split("-"))
                        current = [a, b, 0, 0]
                elif current is not None and head[0] in ("Rss:", "Anonymous:"):
                    current[2 if head[0] == "Rss:" else 3] = int(head[1])
    except (OSError, ValueError):
        return []
    if current is not None and current[3] == 0:
        found.append((current[0], current[1], current[2]))
    return found


def raster_maps(directory: str) -> Callable[[str], bool]:
    """Selects the prepared rasters and grids (`MAPPED_SUFFIXES`) under `directory`."""
    prefix = os.path.join(os.path.realpath(directory), "")
    return lambda path: path.startswith(prefix) and path.endswith(MAPPED_SUFFIXES)


def compiler_library(path: str) -> bool:
    """Selects LLVM's library (`COMPILER_LIBRARIES`), used to compile and load the kernels."""
    return os.path.basename(path) in COMPILER_LIBRARIES


def drop_file_pages(select: Callable[[str], bool]) -> float:
    """Drop the resident pages of the clean file maps `select` accepts; returns their MiB."""
    try:
        madvise = ctypes.CDLL("libc.so.6", use_errno=True).madvise
    except (OSError, AttributeError):
        return 0.0
    madvise.argtypes = (ctypes.c_void_p, ctypes.c_size_t, ctypes.c_int)
    dropped_kib = 0
    for start, end, kib in clean_file_maps(select):
        if kib and madvise(start, end - start, mmap.MADV_DONTNEED) == 0:
            dropped_kib += kib
    return dropped_kib / 1024.0


def release_after_plan(collect: bool, data_directory: str | None = None) -> Released:
    """After a plan: drop the raster pages it touched (maps under `data_directory`, default
    the shiproute data directory) and LLVM's, and return freed heap memory. With `collect`
    (a new cycle's first plan) a full garbage collection runs first, and what the process
    holds then is left out of later collections (`process_tuning.freeze_long_lived`)."""
    rasters = raster_maps(str(data_dir()) if data_directory is None else data_directory)
    file_mb = drop_file_pages(lambda path: rasters(path) or compiler_library(path))  # one pass
    tuning.return_freed_memory(collect=collect)
    if collect:
        tuning.freeze_long_lived()  # after the first plan, which loaded all planning needs
    rss, peak = tuning.memory_mb()
    return Released(file_mb, rss, peak)
