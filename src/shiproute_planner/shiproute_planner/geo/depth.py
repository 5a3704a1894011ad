"""Water depth from several bathymetry grids, finest first, for points and route legs."""

from __future__ import annotations

import functools
from collections.abc import Sequence
from pathlib import Path

import numpy as np
from scipy import ndimage

from . import _depth_kernels as dk
from . import depth_cache
from .bathymetry import DepthGrid, default_depth_files, load_depth_grid
from .coarse_coast import COAST_CELLS

BLOCK_DEG = 0.25  # pre-check raster: minimum known depth per 0.25-deg block


class Bathymetry:
    """Depth lookups over grids ordered finest first (the finest with a value answers)."""

    def __init__(self, grids: Sequence[DepthGrid]) -> None:
        if not grids:
            raise ValueError("Bathymetry needs at least one grid")
        self.grids = tuple(sorted(grids, key=lambda g: g.cell_deg))
        sizes = [g.depth_m.size for g in self.grids]
        offsets = np.concatenate([[0], np.cumsum(sizes)[:-1]])
        # one grid (the default): its own array, memory-mapped when prepared before (no copy)
        self._data = (self.grids[0].depth_m.reshape(-1) if len(self.grids) == 1 else
                      np.concatenate([g.depth_m.ravel() for g in self.grids]
                                     ).astype(np.float32))
        self._table = np.array([[g.lat0_deg, g.dlat_deg, g.lon0_deg, g.dlon_deg,
                                 g.depth_m.shape[0], g.depth_m.shape[1], float(g.periodic),
                                 float(off)] for g, off in zip(self.grids, offsets, strict=True)],
                               dtype=np.float64)
        self._coarse = _coarse_min(self.grids, BLOCK_DEG)

    @property
    def description(self) -> str:
        """What the depths come from, finest first, with each grid's resolution."""
        parts = []
        for g in self.grids:
            note = (f" (coarse: cells within {COAST_CELLS} cells of GSHHG land are smeared and "
                    "give no depth, the coastline decides there; shelf fill values, whole "
                    "metres far more frequent than their neighbours, read as unknown)") if (
                g.is_coarse) else ""
            parts.append(f"{g.name} ({g.resolution_text}){note}")
        return "; ".join(parts)

    @property
    def kernel_grids(self) -> tuple[np.ndarray, np.ndarray]:
        """(all grids' depths flattened, grid table) as `_depth_kernels` reads them."""
        return self._data, self._table

    @property
    def block_minimum(self) -> tuple[np.ndarray, float]:
        """(minimum known depth within one block of each block, +inf unknown; block [deg])."""
        return self._coarse, BLOCK_DEG

    def depth_m(self, lon_deg: np.ndarray, lat_deg: np.ndarray) -> np.ndarray:
        """Depth [m, positive down] at points; NaN where no grid knows it; 0 where dry."""
        lat = np.ascontiguousarray(lat_deg, dtype=float).ravel()
        lon = np.ascontiguousarray(lon_deg, dtype=float).ravel()
        out = np.empty(lat.size)
        dk.depths_at(lat, lon, self._data, self._table, out)
        return out.reshape(np.shape(lat_deg))

    def segment_min_depth_m(self, lon0: np.ndarray, lat0: np.ndarray, lon1: np.ndarray,
                            lat1: np.ndarray, cap_m: np.ndarray | float = np.inf
                            ) -> np.ndarray:
        """Shallowest depth [m] along each great-circle segment (at half the finest grid's
        spacing), capped at `cap_m` (with a finite cap deep water is skipped cheaply); NaN
        where no grid covers the segment."""
        shape = np.shape(lon0)
        x0, y0, x1, y1 = (np.ascontiguousarray(a, dtype=float).ravel()
                          for a in (lon0, lat0, lon1, lat1))
        cap = np.ascontiguousarray(np.broadcast_to(cap_m, shape), dtype=float).ravel()
        out = np.empty(x0.size)
        dk.segment_min_depth(x0, y0, x1, y1, cap, self._data, self._table, self._coarse,
                             BLOCK_DEG, out)
        return out.reshape(shape)


def _coarse_min(grids: Sequence[DepthGrid], block_deg: float) -> np.ndarray:
    """Global raster of the minimum known depth within one block of each block (+inf where
    no grid has a value), row 0 at 90 S and column 0 at 180 W."""
    n_lat, n_lon = round(180.0 / block_deg), round(360.0 / block_deg)
    coarse = np.full((n_lat, n_lon), np.inf, dtype=np.float32)
    for g in grids:
        rows, cols = g.depth_m.shape
        lat_c = g.lat0_deg + g.dlat_deg * np.arange(rows)
        lon_c = g.lon0_deg + g.dlon_deg * np.arange(cols)
        bi = np.clip(((lat_c + 90.0) / block_deg).astype(np.int64), 0, n_lat - 1)
        bj = np.clip((((lon_c + 180.0) % 360.0) / block_deg).astype(np.int64), 0, n_lon - 1)
        r0 = np.flatnonzero(np.r_[True, bi[1:] != bi[:-1]])
        c0 = np.flatnonzero(np.r_[True, bj[1:] != bj[:-1]])
        d = np.where(np.isnan(g.depth_m), np.inf, g.depth_m)
        small = np.minimum.reduceat(np.minimum.reduceat(d, r0, axis=0), c0, axis=1)
        np.minimum.at(coarse, (bi[r0][:, None], bj[c0][None, :]), small.astype(np.float32))
        del d
        depth_cache.drop_resident_pages(g.depth_m)  # the scan read all of a mapped grid
    return ndimage.minimum_filter(coarse, size=3, mode=("nearest", "wrap"))


@functools.lru_cache(maxsize=4)
def _bathymetry(paths: tuple[str, ...]) -> Bathymetry:
    return Bathymetry([load_depth_grid(p) for p in paths])


def load_bathymetry(paths: Sequence[str | Path] = (), with_default: bool = True
                    ) -> Bathymetry | None:
    """Bathymetry from the user's grid files plus (with `with_default`) the bundled coarse
    global grid; None when there is none at all. Cached per set of files."""
    files = [str(Path(p).expanduser().resolve()) for p in paths]
    if with_default:
        files += [str(p) for p in default_depth_files() if str(p) not in files]
    if not files:
        return None
    return _bathymetry(tuple(files))
