"""UTC time helpers: ISO 8601 strings <-> integer nanoseconds since the POSIX epoch."""

from __future__ import annotations

from typing import Literal

import numpy as np


def iso_to_ns(text: str) -> int:
    """Nanoseconds since 1970-01-01T00:00Z of an ISO 8601 UTC time ('Z' or no zone)."""
    t = text.strip()
    if t.endswith("Z"):
        t = t[:-1]
    elif t.endswith("+00:00"):
        t = t[:-6]
    return int(np.datetime64(t, "ns").astype(np.int64))


def ns_to_iso(ns: int) -> str:
    """Canonical ISO 8601 UTC string: seconds resolution unless sub-second parts exist."""
    t = np.datetime64(int(ns), "ns")
    unit: Literal["s", "ns"] = "s" if ns % 1_000_000_000 == 0 else "ns"
    return str(np.datetime_as_string(t, unit=unit)) + "Z"


def canonical_iso(text: str) -> str:
    """Reformat any ISO 8601 UTC time to the canonical form used in dataset attrs."""
    return ns_to_iso(iso_to_ns(text))
