"""Read an RTZ route file (IEC 61174, versions 1.0-1.2): waypoints, leg speeds and schedule.

The one RTZ reader of shiproute: the route check reads the track from it, the voyage simulator
the schedule as well. Tags are matched without their namespace, so every RTZ version reads.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import RouteFileError


@dataclass(frozen=True)
class RtzRoute:
    """Waypoints in file order (as written, not unwrapped) and what the file says of each leg."""

    name: str  # routeName, else the file stem
    waypoint_ids: tuple[str, ...]
    lon_deg: np.ndarray
    lat_deg: np.ndarray
    leg_speed_max_kn: np.ndarray  # per leg (n - 1): <leg speedMax> of its end waypoint, or NaN
    # waypointId -> scheduleElement attributes of the first calculated (else manual) schedule
    schedule: dict[str, dict[str, str]] = field(default_factory=dict)


def local_tag(tag: str) -> str:
    """An XML tag without its namespace."""
    return tag.rsplit("}", 1)[-1]


def _schedule(root: ET.Element) -> dict[str, dict[str, str]]:
    for kind in ("calculated", "manual"):
        found = [e for e in root.iter() if local_tag(e.tag) == kind]
        if found:
            return {e.get("waypointId", ""): dict(e.attrib) for e in found[0].iter()
                    if local_tag(e.tag) == "scheduleElement"}
    return {}


def read_rtz(path: str | Path) -> RtzRoute:
    """Parse `path` as RTZ; RouteFileError names the file and what is wrong with it."""
    path = Path(path)
    try:
        root = ET.parse(path).getroot()
    except OSError as exc:
        raise RouteFileError(f"route file {path}: cannot be read ({exc})") from None
    except ET.ParseError as exc:
        raise RouteFileError(f"route file {path}: not well-formed XML ({exc})") from None
    if local_tag(root.tag) != "route":
        raise RouteFileError(f"route file {path}: root element is <{local_tag(root.tag)}>, "
                             "not an RTZ <route>")
    ids: list[str] = []
    lat: list[float] = []
    lon: list[float] = []
    speed: list[float] = []
    for wp in root.iter():
        if local_tag(wp.tag) != "waypoint":
            continue
        pos = next((c for c in wp if local_tag(c.tag) == "position"), None)
        if pos is None:
            continue
        try:
            lat.append(float(pos.attrib["lat"]))
            lon.append(float(pos.attrib["lon"]))
        except (KeyError, ValueError):
            raise RouteFileError(f"route file {path}: waypoint {wp.attrib.get('id', '?')} has "
                                 "no numeric position lat/lon") from None
        leg = next((c for c in wp if local_tag(c.tag) == "leg"), None)
        speed.append(_float(leg.attrib.get("speedMax")) if leg is not None else np.nan)
        ids.append(wp.attrib.get("id", str(len(ids) + 1)))
    name = next((e.attrib.get("routeName", "") for e in root.iter()
                 if local_tag(e.tag) == "routeInfo"), "") or path.stem
    # RTZ: a waypoint's <leg> describes the leg arriving at it
    return RtzRoute(name, tuple(ids), np.asarray(lon, dtype=float), np.asarray(lat, dtype=float),
                    np.asarray(speed[1:], dtype=float), _schedule(root))


def _float(text: str | None) -> float:
    """A number from an attribute; NaN when absent or not a number."""
    if not text:
        return np.nan
    try:
        return float(text)
    except ValueError:
        return np.nan
