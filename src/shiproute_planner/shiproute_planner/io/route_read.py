"""Read a route to check: RTZ (1.0-1.2, e.g. exported from an ECDIS) or GeoJSON lines."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import RouteFileError


@dataclass(frozen=True)
class RouteTrack:
    """Waypoints of a route in sailing order and, where the file gives it, speed per leg."""

    name: str
    lon_deg: np.ndarray  # continuous longitudes
    lat_deg: np.ndarray
    speed_kn: np.ndarray  # per leg, NaN where the file has none


def _local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1]


def _read_rtz(path: Path) -> RouteTrack:
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as exc:
        raise RouteFileError(f"route file {path}: not well-formed XML ({exc})") from None
    if _local(root.tag) != "route":
        raise RouteFileError(f"route file {path}: root element is <{_local(root.tag)}>, "
                             "not an RTZ <route>")
    lat: list[float] = []
    lon: list[float] = []
    speed: list[float] = []
    ids: list[str] = []
    for wp in root.iter():
        if _local(wp.tag) != "waypoint" or not any(_local(c.tag) == "position" for c in wp):
            continue
        pos = next(c for c in wp if _local(c.tag) == "position")
        try:
            lat.append(float(pos.attrib["lat"]))
            lon.append(float(pos.attrib["lon"]))
        except (KeyError, ValueError):
            raise RouteFileError(f"route file {path}: waypoint {wp.attrib.get('id', '?')} has "
                                 "no numeric position lat/lon") from None
        leg = next((c for c in wp if _local(c.tag) == "leg"), None)
        speed.append(float(leg.attrib.get("speedMax", "nan")) if leg is not None else np.nan)
        ids.append(wp.attrib.get("id", str(len(ids) + 1)))
    name = next((e.attrib.get("routeName", "") for e in root.iter()
                 if _local(e.tag) == "routeInfo"), "") or path.stem
    # RTZ: a waypoint's <leg> describes the leg arriving at it
    return _track(path, name, lon, lat, speed[1:] if speed else [])


def _read_geojson(path: Path) -> RouteTrack:
    try:
        data = json.loads(path.read_text())
    except (UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise RouteFileError(f"route file {path}: not valid JSON ({exc})") from None
    feats = data.get("features", [data]) if isinstance(data, dict) else []
    lon: list[float] = []
    lat: list[float] = []
    speed: list[float] = []
    for f in feats:
        geom = f.get("geometry", f) if isinstance(f, dict) else None
        if not isinstance(geom, dict) or geom.get("type") not in ("LineString",
                                                                   "MultiLineString"):
            continue
        lines = geom["coordinates"] if geom["type"] == "MultiLineString" else [
            geom["coordinates"]]
        props = f.get("properties") or {}
        v = props.get("sog_kn", props.get("stw_kn", props.get("speed_kn")))
        v = float(v) if isinstance(v, int | float) else np.nan
        for line in lines:
            pts = [(float(p[0]), float(p[1])) for p in line]
            joined = bool(lon and pts and abs(pts[0][0] - lon[-1]) < 1e-9
                          and abs(pts[0][1] - lat[-1]) < 1e-9)
            if joined:
                pts = pts[1:]  # joined legs share their end points
            for j, (x, y) in enumerate(pts):
                if lon:  # the leg arriving here: this line's, or a gap sailed straight
                    speed.append(v if (j > 0 or joined) else np.nan)
                lon.append(x)
                lat.append(y)
    if not lon:
        raise RouteFileError(f"route file {path}: no LineString in the GeoJSON")
    return _track(path, path.stem, lon, lat, speed)


def _track(path: Path, name: str, lon: list[float], lat: list[float],
           speed: list[float]) -> RouteTrack:
    if len(lon) < 2:
        raise RouteFileError(f"route file {path}: {len(lon)} waypoint(s); a route needs at "
                             "least 2")
    la, lo = np.asarray(lat, dtype=float), np.asarray(lon, dtype=float)
    if np.any(np.abs(la) > 90) or np.any(np.abs(lo) > 540) or not np.all(np.isfinite(la + lo)):
        raise RouteFileError(f"route file {path}: positions out of range (lat must be in "
                             "-90..90, lon in degrees)")
    sp = np.full(lo.size - 1, np.nan)
    sp[: min(len(speed), sp.size)] = speed[: sp.size]
    return RouteTrack(name, np.unwrap(lo, period=360.0), la, sp)


def read_route(path: str | Path) -> RouteTrack:
    """Read an RTZ or GeoJSON route file (by content: XML or JSON)."""
    path = Path(path)
    if not path.is_file():
        raise RouteFileError(f"route file {path} does not exist")
    head = path.read_bytes()[:200].lstrip()
    if head.startswith(b"<"):
        return _read_rtz(path)
    if head.startswith((b"{", b"[")):
        return _read_geojson(path)
    raise RouteFileError(f"route file {path}: neither RTZ (XML) nor GeoJSON")
