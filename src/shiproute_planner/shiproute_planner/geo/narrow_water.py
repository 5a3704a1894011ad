"""How much room the water round each level-0 cell has: the sea-area type of the clearance rule.

Per 0.05-deg cell of the finest coastline's level 0 (`geo.coast_distance`, a lower bound of the
distance to land, 0 in the coastal band about two cells each side of a coast), the room is the
largest level-0 distance within `ROOM_RADIUS_NM` of any point within `NARROW_REACH_NM` (a
maximum filter, then a minimum filter, on discs scaled by the cosine of each latitude band);
outside the band the bound's cell diagonal is added back (a mid estimate, not a bound: the room
only sorts water into types, and without it a small island's own cells, ~5 NM under their true
distance, read as narrow water). Why these radii: `ROOM_RADIUS_NM` = 10 NM is about half a
coastal stage leg; near a straight coast in open water the room is then at least ~5 NM (the
coastal band is ~6 NM wide), while in a channel or strait narrower than ~10 NM every cell is in
the band and the room is ~0. The minimum over `NARROW_REACH_NM` = 5 NM carries a narrow
passage's type out beyond its mouths, so a route leaving it is not held to the open-sea
clearance while the coast is still near (the open-sea distance can only grow by the distance
sailed). Stored as uint8 tenths of a NM (capped at 25.4 NM), built once per machine and
memory-mapped.
"""

from __future__ import annotations

import functools
import math
import os

import numpy as np

from .coast_distance import NM_PER_DEG

ROOM_VERSION = 2  # in the cache file name: bump when the definition changes
ROOM_RADIUS_NM = 10.0
NARROW_REACH_NM = 5.0
UNIT_NM = 0.1  # stored value * UNIT_NM = room [NM]
CAP_UNITS = 254
BAND_ROWS = 40  # latitude rows per filter band (2 deg of 0.05-deg cells)


def _disc(radius_nm: float, cell_nm: float, shrink: float) -> np.ndarray:
    """Footprint of the cells whose centres lie within `radius_nm` of a cell's centre."""
    rows = math.ceil(radius_nm / cell_nm)
    cols = math.ceil(radius_nm / (cell_nm * shrink))
    y, x = np.mgrid[-rows:rows + 1, -cols:cols + 1]
    return (y * cell_nm) ** 2 + (x * cell_nm * shrink) ** 2 <= radius_nm ** 2 + 1e-9


def _banded(values: np.ndarray, cell_deg: float, radius_nm: float, maximum: bool
            ) -> np.ndarray:
    """Maximum (or minimum) of `values` (global raster, row 0 at 90 S) over a disc of
    `radius_nm` round each cell, longitudes wrapping round the globe."""
    from scipy import ndimage

    n_lat, n_lon = values.shape
    cell_nm = cell_deg * NM_PER_DEG
    out = np.empty_like(values)
    rows = math.ceil(radius_nm / cell_nm)
    filt = ndimage.maximum_filter if maximum else ndimage.minimum_filter
    for a in range(0, n_lat, BAND_ROWS):
        b = min(a + BAND_ROWS, n_lat)
        equatorward = min(abs(-90.0 + a * cell_deg), abs(-90.0 + b * cell_deg))
        shrink = max(math.cos(math.radians(equatorward)), 0.05)
        disc = _disc(radius_nm, cell_nm, shrink)
        cols = min(disc.shape[1] // 2, n_lon)
        ra, rb = max(a - rows, 0), min(b + rows, n_lat)
        block = np.concatenate([values[ra:rb, n_lon - cols:], values[ra:rb],
                                values[ra:rb, :cols]], axis=1)
        done = filt(block, footprint=disc, mode="nearest")
        out[a:b] = done[a - ra:b - ra, cols:cols + n_lon]
    return out


def room_raster(coast_dist: np.ndarray, cell_deg: float, coast_unit_nm: float) -> np.ndarray:
    """uint8 room [UNIT_NM] of each cell of a level-0 raster (`coast_dist` in
    `coast_unit_nm` steps; see the module docstring)."""
    scale = coast_unit_nm / UNIT_NM
    d = np.asarray(coast_dist, dtype=np.float32) * scale
    diagonal = math.hypot(cell_deg, cell_deg) * NM_PER_DEG / UNIT_NM
    clipped = np.clip(np.where(d > 0, d + diagonal, 0.0), 0, CAP_UNITS)
    values = np.floor(clipped).astype(np.uint8)
    room = _banded(values, cell_deg, ROOM_RADIUS_NM, maximum=True)
    return _banded(room, cell_deg, NARROW_REACH_NM, maximum=False)


@functools.lru_cache(maxsize=2)
def default_room() -> np.ndarray:
    """The room raster of the finest coastline installed (`geo.full_land`), from the data
    directory (built and stored atomically the first time)."""
    from .coast_distance import UNIT_NM as L0_UNIT_NM
    from .datadir import data_dir
    from .full_land import final_land

    mask = final_land().mask
    path = data_dir() / (f"room_v{ROOM_VERSION}_gshhg_{mask.resolution}_{mask.cell_deg:g}deg"
                         ".npy")
    if path.is_file():
        try:
            return np.load(path, mmap_mode="r")
        except (OSError, ValueError):
            pass  # corrupt cache: rebuild below
    room = room_raster(np.asarray(mask.coast_distance), mask.cell_deg, L0_UNIT_NM)
    tmp = path.with_suffix(f".{os.getpid()}.tmp.npy")
    try:
        np.save(tmp, room)
        os.replace(tmp, path)
    except OSError:
        tmp.unlink(missing_ok=True)
    return room


NARROWS_ROOM_UNITS = 10  # room written round a lane's narrows: narrow water, not tight water


@functools.lru_cache(maxsize=4)
def room_with_narrows(narrows: tuple[tuple[float, float], ...], reach_nm: float) -> np.ndarray:
    """The room raster with every cell within `reach_nm` of a narrows point ((lon, lat)
    [deg]; `route.lane_narrows`) lowered to narrow water (1 NM: the approach clearance
    there, land still tested at full resolution)."""
    base = default_room()
    if not narrows:
        return base
    room = np.array(base)
    n_lat, n_lon = room.shape
    cell = 180.0 / n_lat
    rows = math.ceil(reach_nm / (cell * 60.0)) + 1
    for lon, lat in narrows:
        i0 = int((lat + 90.0) // cell)
        shrink = max(math.cos(math.radians(min(abs(lat) + rows * cell, 89.0))), 0.05)
        cols = math.ceil(reach_nm / (cell * 60.0 * shrink)) + 1
        i = np.arange(max(i0 - rows, 0), min(i0 + rows + 1, n_lat))
        j = (int(((lon + 180.0) % 360.0) // cell) + np.arange(-cols, cols + 1)) % n_lon
        c_lat = -90.0 + (i + 0.5) * cell
        c_lon = -180.0 + (j + 0.5) * cell
        d_lat = (c_lat[:, None] - lat) * 60.0
        d_lon = ((c_lon[None, :] - lon + 180.0) % 360.0 - 180.0) * 60.0 * np.cos(
            np.radians(c_lat[:, None]))
        near = np.hypot(d_lat, d_lon) <= reach_nm + cell * 60.0  # any part of the cell
        block = room[np.ix_(i, j)]
        room[np.ix_(i, j)] = np.where(near, np.minimum(block, NARROWS_ROOM_UNITS), block)
    return room


def room_for(narrows: tuple[tuple[float, float], ...], reach_nm: float) -> np.ndarray:
    """The room raster a clearance rule with `narrows` reads (the shared one without)."""
    return room_with_narrows(narrows, reach_nm) if narrows else default_room()
