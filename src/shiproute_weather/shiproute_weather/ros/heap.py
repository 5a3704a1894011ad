"""Give freed heap memory back to the OS (glibc), so a node loading cycle after cycle stays flat;
and say how much the process holds.

A load holds the decoded dataset (~180 MB float32 for the 16-day storm cycle) and its encoded
slices for a moment; glibc keeps freed blocks in the heap otherwise, and by its dynamic mmap
threshold serves later blocks of up to 32 MB from the heap too, so the node's resident memory
ratchets up with every load. No-ops where glibc is absent.
"""

from __future__ import annotations

import contextlib
import ctypes
import gc

_M_MMAP_THRESHOLD = -3  # glibc mallopt parameter


def _libc() -> ctypes.CDLL | None:
    try:
        return ctypes.CDLL("libc.so.6")
    except OSError:
        return None


def return_large_blocks_at_once(threshold_bytes: int = 1 << 19) -> None:
    """Serve allocations from `threshold_bytes` (512 KiB) up by mmap: a slice message's field
    arrays (0.7 MB packed) and the dataset go back to the OS when freed. Setting it also turns
    off glibc's dynamic threshold, which would otherwise climb to 32 MB."""
    libc = _libc()
    if libc is not None:
        with contextlib.suppress(AttributeError):
            libc.mallopt(_M_MMAP_THRESHOLD, int(threshold_bytes))


def return_freed_memory() -> None:
    """Collect garbage, then hand the heap's free pages back to the OS (malloc_trim)."""
    gc.collect()
    libc = _libc()
    if libc is not None:
        with contextlib.suppress(AttributeError):
            libc.malloc_trim(0)


def resident_memory_mb() -> dict[str, str]:
    """This process's resident memory now and at its peak [MiB] (Linux VmRSS, VmHWM), as
    diagnostics values; empty where /proc is absent."""
    keys = {"VmRSS:": "resident_mb", "VmHWM:": "resident_peak_mb"}
    out: dict[str, str] = {}
    with contextlib.suppress(OSError, ValueError, IndexError), \
            open("/proc/self/status") as f:
        for line in f:
            name = keys.get(line.split(":", 1)[0] + ":")
            if name is not None:
                out[name] = f"{int(line.split()[1]) / 1024:.1f}"
    return out
