"""Independent land and depth audit of plan GeoJSON files (a check script, not product code).

Written for the hold-out world check (`shiproute bench world --lanes holdout --out DIR`):
the planner's own route check is not trusted to judge itself. Every leg of the GeoJSON track
is densified on the WGS 84 ellipsoid (pyproj) every 0.25 NM and each sample is tested with
shapely against the GSHHG full-resolution land rings (read by `geo.gshhg`, nothing else of
the product's land code); samples within 3 NM of a port point or a route end and within 2 NM
of a canal's line (fixed passages) are ignored. Depth: the ETOPO5 cell under each sample
(nearest) counts as shallow when it and its 8 neighbours are all water and all shallower than
the ship's design draft (open-water shoals; at 5 arc-minutes cells next to land are smeared
and are not judged), outside 10 NM of a port.

usage: ros2_ws/.venv/bin/python ros2_ws/tools/holdout_land_check.py DRAFTS_JSON PLAN.geojson...
DRAFTS_JSON maps ship names to design drafts [m]; prints one JSON line per plan.
"""

from __future__ import annotations

import functools
import itertools
import json
import sys
from pathlib import Path

import netCDF4
import numpy as np
import shapely
from pyproj import Geod
from shiproute_planner.geo.gshhg import load_land_polygons
from shiproute_planner.route.canals import CANALS

M_PER_NM = 1852.0
STEP_NM = 0.25
GEOD = Geod(ellps="WGS84")
ETOPO5 = "/usr/share/ferret-vis/data/etopo5.cdf"


def samples(coords: list) -> tuple[np.ndarray, np.ndarray]:
    """Points every STEP_NM along the polyline's geodesics (lon in -180..180, lat)."""
    lon, lat = [], []
    for (lo1, la1), (lo2, la2) in itertools.pairwise(coords):
        _, _, d = GEOD.inv(lo1, la1, lo2, la2)
        n = int(np.ceil(d / (STEP_NM * M_PER_NM)))
        for lo, la in [(lo1, la1), *(GEOD.npts(lo1, la1, lo2, la2, n - 1) if n > 1 else [])]:
            lon.append((lo + 180.0) % 360.0 - 180.0)
            lat.append(la)
    lon.append((coords[-1][0] + 180.0) % 360.0 - 180.0)
    lat.append(coords[-1][1])
    return np.array(lon), np.array(lat)


def near(lon: np.ndarray, lat: np.ndarray, points: list, radius_m: float) -> np.ndarray:
    """True where a sample lies within `radius_m` of any (lon, lat) of `points`."""
    out = np.zeros(lon.size, dtype=bool)
    pad_lat = radius_m / 1.0e5 + 0.01
    for p_lon, p_lat in points:
        pad_lon = pad_lat / max(float(np.cos(np.radians(p_lat))), 0.05)
        close = np.flatnonzero((np.abs(lat - p_lat) < pad_lat)
                               & (np.abs((lon - p_lon + 180.0) % 360.0 - 180.0) < pad_lon))
        if close.size:
            _, _, d = GEOD.inv(np.full(close.size, p_lon), np.full(close.size, p_lat),
                               lon[close], lat[close])
            out[close[d < radius_m]] = True
    return out


def on_land(lon: np.ndarray, lat: np.ndarray, chunk: int = 400) -> np.ndarray:
    """True where a sample lies inside a GSHHG full-resolution land ring (rings near each
    chunk of consecutive samples only: a long track's bounding box holds most of the world)."""
    poly = load_land_polygons("f")
    b = poly.bounds
    built: dict[int, shapely.Polygon] = {}
    hit = np.zeros(lon.size, dtype=bool)
    for s0 in range(0, lon.size, chunk):
        c_lon, c_lat = lon[s0:s0 + chunk], lat[s0:s0 + chunk]
        idx = np.flatnonzero((b[:, 0] <= c_lon.max()) & (b[:, 2] >= c_lon.min())
                             & (b[:, 1] <= c_lat.max()) & (b[:, 3] >= c_lat.min()))
        for i in idx:
            if int(i) not in built:
                ring = shapely.Polygon(poly.ring(int(i)))
                ring = ring if ring.is_valid else ring.buffer(0)
                shapely.prepare(ring)
                built[int(i)] = ring
            x0, y0, x1, y1 = b[i]
            sel = np.flatnonzero((c_lon >= x0) & (c_lon <= x1) & (c_lat >= y0) & (c_lat <= y1))
            if sel.size:
                hit[s0 + sel] |= shapely.contains_xy(built[int(i)], c_lon[sel], c_lat[sel])
    return hit


@functools.lru_cache(maxsize=1)
def etopo5() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """ETOPO5 elevation [m, up], longitudes and latitudes (read once)."""
    with netCDF4.Dataset(ETOPO5) as ds:
        return (np.asarray(ds.variables["ROSE"][:], dtype=float),
                np.asarray(ds.variables["ETOPO05_X"][:], dtype=float),
                np.asarray(ds.variables["ETOPO05_Y"][:], dtype=float))


def open_water_shoals(lon: np.ndarray, lat: np.ndarray, draft_m: float
                      ) -> tuple[np.ndarray, np.ndarray]:
    """(shallow, depth [m]) from ETOPO5: shallow where the 3 x 3 cells round the sample are
    all water and all shallower than `draft_m`."""
    elev, x, y = etopo5()
    i = np.clip(np.searchsorted(y, lat), 1, y.size - 2)
    j = np.searchsorted(x, lon % 360.0) % x.size
    deepest = np.full(lon.size, -np.inf)
    shallowest = np.full(lon.size, np.inf)
    for di in (-1, 0, 1):
        for dj in (-1, 0, 1):
            d = -elev[i + di, (j + dj) % x.size]
            deepest = np.maximum(deepest, d)
            shallowest = np.minimum(shallowest, d)
    return (deepest < draft_m) & (shallowest > 0.0), -elev[i, j]


def runs_nm(mask: np.ndarray) -> list[tuple[int, int]]:
    """(first sample, length) of each run of True."""
    out: list[tuple[int, int]] = []
    for k in np.flatnonzero(mask):
        if out and out[-1][0] + out[-1][1] == k:
            out[-1] = (out[-1][0], out[-1][1] + 1)
        else:
            out.append((int(k), 1))
    return out


def check(path: Path, drafts: dict[str, float]) -> dict:
    """The audit of one plan's GeoJSON (and its JSON beside it, for ship and warnings)."""
    features = json.loads(path.read_text())["features"]
    lines = [f["geometry"]["coordinates"] for f in features
             if f["geometry"]["type"] == "LineString"]
    coords = [lines[0][0]] + [c for line in lines for c in line[1:]]
    ports = [tuple(f["geometry"]["coordinates"][:2]) for f in features
             if f["geometry"]["type"] == "Point"] + [tuple(coords[0]), tuple(coords[-1])]
    lon, lat = samples(coords)
    skip = near(lon, lat, ports, 3 * M_PER_NM)
    for canal in CANALS:
        c_lon, c_lat = samples([(p[1], p[0]) for p in canal.line])
        skip |= near(lon, lat, list(zip(c_lon, c_lat, strict=True)), 2 * M_PER_NM)
    land = on_land(lon, lat) & ~skip
    plan = json.loads(path.with_suffix(".json").read_text())
    draft = drafts[plan["ship"]]
    shallow, depth = open_water_shoals(lon, lat, draft)
    shallow &= ~near(lon, lat, ports, 10 * M_PER_NM)
    return {
        "plan": path.stem, "samples": int(lon.size),
        "land_nm": round(float(land.sum()) * STEP_NM, 2),
        "land_runs": [(round(float(lat[k]), 3), round(float(lon[k]), 3), round(n * STEP_NM, 2))
                      for k, n in runs_nm(land)][:8],
        "plan_says_depth_checked": not any(w.startswith("depth not checked:")
                                           for w in plan["warnings"]),
        "draft_m": draft, "etopo5_open_water_shoal_nm": round(float(shallow.sum()) * STEP_NM, 2),
        "etopo5_shoals": [(round(float(lat[k]), 3), round(float(lon[k]), 3),
                           round(float(depth[k]), 0)) for k, _ in runs_nm(shallow)][:6],
    }


def main(argv: list[str]) -> int:
    """Audit every GeoJSON named on the command line."""
    drafts = json.loads(argv[0])
    for name in argv[1:]:
        print(json.dumps(check(Path(name), drafts)), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
