"""Process settings of the planner node: glibc heap returns, a frozen garbage-collector
generation, a short GIL switch interval and the resident memory read from /proc.

A forecast cycle streams ~130 slice buffers of ~1.4 MB through the process; glibc keeps freed
blocks in its heap unless told otherwise, and a full garbage collection over everything the
planner loaded holds the GIL long enough to stall the slice intake. These calls keep both in
check; they are no-ops where glibc or /proc are missing.
"""

from __future__ import annotations

import contextlib
import ctypes
import gc
import math
import sys

#: glibc `mallopt` parameter number of the mmap threshold (malloc.h, M_MMAP_THRESHOLD)
M_MMAP_THRESHOLD = -3
#: allocations from this size up are served by mmap: a packed slice's fields are 0.7 MB,
#: float32 ones 1.4 MB, so their memory goes back to the OS when freed
MMAP_THRESHOLD_BYTES = 1 << 19
#: the GIL is handed over this often: the forecast intake thread waits behind the executor
#: threads otherwise (the default is 5 ms); planning threads run compiled code without the GIL
SWITCH_INTERVAL_S = 0.001


def return_freed_memory(collect: bool = True) -> None:
    """Hand freed heap memory back to the OS: glibc keeps freed blocks otherwise, and a cycle
    leaves its freed slice buffers behind. malloc_trim runs without the GIL (ctypes), so it
    may overlap planning; the garbage collection (optional) does not."""
    if collect:
        gc.collect()
    with contextlib.suppress(OSError, AttributeError):  # not glibc: nothing to do
        ctypes.CDLL("libc.so.6").malloc_trim(0)


def freeze_long_lived() -> None:
    """Leave what the process holds now (modules, compiled kernels, coastline, tables) out of
    all later garbage collections: a full collection walks them with the GIL held, stalling
    slice intake and planning whenever one falls into a re-plan. Call it right after a full
    collection, so no garbage is kept (Python docs, `gc.freeze`); only the first call freezes."""
    if gc.get_freeze_count() == 0:
        gc.freeze()


def return_large_blocks_at_once() -> None:
    """Serve large allocations by mmap, so their memory goes back to the OS when freed instead
    of piling up in the heap while a cycle streams in."""
    with contextlib.suppress(OSError, AttributeError):
        ctypes.CDLL("libc.so.6").mallopt(M_MMAP_THRESHOLD, MMAP_THRESHOLD_BYTES)


def hand_over_gil_often() -> None:
    """Shorten the interpreter's switch interval so the intake thread gets the GIL promptly."""
    sys.setswitchinterval(SWITCH_INTERVAL_S)


def memory_mb() -> tuple[float, float]:
    """Resident memory of this process and its high-water mark [MiB] (Linux; NaN elsewhere)."""
    values = {"VmRSS:": math.nan, "VmHWM:": math.nan}
    try:
        with open("/proc/self/status") as f:
            for line in f:
                key = line.split(":", 1)[0] + ":"
                if key in values:
                    values[key] = int(line.split()[1]) / 1024
    except (OSError, ValueError, IndexError):
        pass
    return values["VmRSS:"], values["VmHWM:"]
