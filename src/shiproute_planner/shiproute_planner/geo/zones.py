"""No-go and avoid-if-possible areas from GeoJSON polygons (exercise areas, ice limits,
high-risk areas, ECAs), each a hard constraint or a penalty per nautical mile inside.

Feature properties: `name` (optional), `mode` = "hard" (default) or "penalty", and for
penalty zones `penalty_per_nm` (objective units per NM sailed inside, default 1.0: with the
fuel objective, tonnes per NM). Coordinates are WGS 84 longitude/latitude (RFC 7946).
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import shapely

from ..errors import ZoneFileError


@dataclass(frozen=True, eq=False)
class Zone:
    """One area: a (multi)polygon in lon/lat degrees, hard or with a penalty per NM."""

    name: str
    geometry: shapely.Geometry
    hard: bool = True
    penalty_per_nm: float = 0.0


@dataclass(frozen=True, eq=False)
class Zones:
    """A set of zones; legs are tested as polylines of chords along their great circles."""

    zones: tuple[Zone, ...]
    source: str = ""

    def __post_init__(self) -> None:
        for z in self.zones:
            shapely.prepare(z.geometry)

    def leg_inside(self, lon0: np.ndarray, lat0: np.ndarray, lon1: np.ndarray,
                   lat1: np.ndarray, samples: int = 16) -> np.ndarray:
        """(n_zones, n_legs) share [0..1] of each leg's length inside each zone: the length of
        its polyline of `samples` chords along the great circle that lies in the zone (exact
        for that polyline, so a leg that clips a corner between two chord ends counts)."""
        shape = np.shape(lon0)
        ends = [np.asarray(a, dtype=float).ravel() for a in (lon0, lat0, lon1, lat1)]
        n = ends[0].size
        out = np.zeros((len(self.zones), n))
        if n == 0 or not self.zones:
            return out.reshape((len(self.zones), *shape))
        lo = np.minimum(ends[0], ends[2]) - 1.0
        hi = np.maximum(ends[0], ends[2]) + 1.0
        la0 = np.minimum(ends[1], ends[3]) - 1.0
        la1 = np.maximum(ends[1], ends[3]) + 1.0
        for zi, z in enumerate(self.zones):
            x0, y0, x1, y1 = shapely.bounds(z.geometry)
            near = (la1 >= y0) & (la0 <= y1)
            lon_ok = np.zeros(n, dtype=bool)
            for shift in (-360.0, 0.0, 360.0):
                lon_ok |= (hi + shift >= x0) & (lo + shift <= x1)
            idx = np.flatnonzero(near & lon_ok)
            if idx.size == 0:
                continue
            pts_lon, pts_lat = gc_samples(ends[0][idx], ends[1][idx], ends[2][idx],
                                          ends[3][idx], samples)
            pts_lon = np.unwrap(pts_lon, period=360.0, axis=1)  # each leg continuous,
            pts_lon += ((pts_lon[:, :1] - x0 + 180.0) % 360.0 - 180.0 + x0) - pts_lon[:, :1]
            lines = shapely.linestrings(np.stack([pts_lon, pts_lat], axis=-1))  # zone's frame
            length = shapely.length(lines)
            cross = shapely.intersects(lines, z.geometry) & (length > 0.0)
            if cross.any():
                inside = shapely.length(shapely.intersection(lines[cross], z.geometry))
                out[zi, idx[cross]] = np.clip(inside / length[cross], 0.0, 1.0)
        return out.reshape((len(self.zones), *shape))


def gc_samples(lon0, lat0, lon1, lat1, samples: int) -> tuple[np.ndarray, np.ndarray]:
    """(n, samples + 1) points along each great-circle segment (normalised chord), deg."""
    def unit(lon, lat):
        lo, la = np.radians(lon), np.radians(lat)
        return np.stack([np.cos(la) * np.cos(lo), np.cos(la) * np.sin(lo), np.sin(la)], -1)

    a, b = unit(lon0, lat0), unit(lon1, lat1)
    f = np.linspace(0.0, 1.0, samples + 1)[None, :, None]
    p = a[:, None, :] + f * (b - a)[:, None, :]
    r = np.linalg.norm(p, axis=-1)
    return (np.degrees(np.arctan2(p[..., 1], p[..., 0])),
            np.degrees(np.arcsin(np.clip(p[..., 2] / r, -1.0, 1.0))))


def load_zones(path: str | Path) -> Zones:
    """Zones from a GeoJSON file of Polygon/MultiPolygon features (clear errors otherwise)."""
    path = Path(path)
    if not path.is_file():
        raise ZoneFileError(f"zone file {path} does not exist")
    try:
        data = json.loads(path.read_text())
    except (UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise ZoneFileError(f"zone file {path} is not GeoJSON: {exc}") from None
    if not isinstance(data, dict) or data.get("type") not in ("FeatureCollection", "Feature",
                                                              "Polygon", "MultiPolygon"):
        raise ZoneFileError(f"zone file {path} is not GeoJSON: expected a FeatureCollection, "
                            "Feature, Polygon or MultiPolygon object")
    feats = data.get("features") if data["type"] == "FeatureCollection" else [
        data if data["type"] == "Feature" else {"type": "Feature", "geometry": data}]
    zones = []
    for k, f in enumerate(feats or []):
        props = (f.get("properties") or {}) if isinstance(f, dict) else {}
        name = str(props.get("name") or f"zone {k + 1}")
        geom = f.get("geometry") if isinstance(f, dict) else None
        if not isinstance(geom, dict) or geom.get("type") not in ("Polygon", "MultiPolygon"):
            kind = geom.get("type") if isinstance(geom, dict) else type(geom).__name__
            raise ZoneFileError(f"zone file {path}: {name} is a {kind}, not a Polygon or "
                                "MultiPolygon")
        try:
            shape = shapely.geometry.shape(geom)
        except (ValueError, TypeError, IndexError, AttributeError) as exc:
            raise ZoneFileError(f"zone file {path}: {name} has invalid coordinates ({exc})"
                                ) from None
        if not shape.is_valid:
            shape = shapely.make_valid(shape)
        mode = str(props.get("mode", "hard")).lower()
        if mode not in ("hard", "penalty"):
            raise ZoneFileError(f"zone file {path}: {name} has mode {mode!r}; use 'hard' or "
                                "'penalty'")
        penalty = props.get("penalty_per_nm", 1.0)
        if not isinstance(penalty, int | float) or penalty < 0:
            raise ZoneFileError(f"zone file {path}: {name} penalty_per_nm {penalty!r} must be "
                                "a non-negative number")
        zones.append(Zone(name, shape, mode == "hard", float(penalty) if mode == "penalty"
                          else 0.0))
    if not zones:
        raise ZoneFileError(f"zone file {path} holds no polygons")
    return Zones(tuple(zones), str(path))
