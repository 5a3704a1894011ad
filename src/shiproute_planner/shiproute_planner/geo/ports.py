"""Port gazetteer: names, UN/LOCODEs and "lat,lon" strings -> positions at sea.

Names come from the `searoute` port list (3,955 ports, some under historical names such as
Pusan for Busan); a small alias table maps common modern names to them. A name also matches
without accents, without the gazetteer's qualifiers ("Seattle (WA)", "Cebu City",
"Padang (Teluk Bajur), Sumatra") and, when several ports far apart share it, the plan says
which was chosen. Port coordinates that fall on the GSHHG coastline are moved to the nearest
water within `max_snap_km`.
"""

from __future__ import annotations

import dataclasses
import difflib
import functools
import json
import re
import unicodedata
from dataclasses import dataclass
from importlib import resources

import numpy as np
from shiproute_core.geodesy import inverse

from ..errors import PortNotFoundError, PositionOnLandError
from .landmask import LandMask
from .port_aliases import ALIASES, LOCODE_FIXES, RIVER_PORTS
from .river_ends import MAX_RIVER_NM, SNAP_KM, river_note, seaward_end

_AMBIGUOUS_KM = 50.0  # ports sharing a name this far apart are different ports
_LATLON = re.compile(r"^\s*([-+]?\d+(?:\.\d*)?)\s*[, ]\s*([-+]?\d+(?:\.\d*)?)\s*$")


@dataclass(frozen=True)
class Port:
    """A resolved port or position: name, UN/LOCODE ('' for coordinates), position at sea."""

    name: str
    locode: str
    lat_deg: float
    lon_deg: float
    snapped_km: float = 0.0  # how far the given position was moved to reach water
    note: str = ""  # what the plan should say about this port (river port, snapped)
    # a port up a river: the gazetteer's berth, while (lat, lon) is the channel's seaward end
    berth_lat_deg: float | None = None
    berth_lon_deg: float | None = None

    @property
    def is_river_port(self) -> bool:
        """True when the port is planned from its river or channel's seaward end."""
        return self.berth_lat_deg is not None and self.berth_lon_deg is not None


def _fold(name: str) -> str:
    """Lower case without accents (Ålesund -> alesund, Málaga -> malaga)."""
    text = unicodedata.normalize("NFKD", name.strip().lower())
    return "".join(c for c in text if not unicodedata.combining(c))


def _short_names(name: str) -> set[str]:
    """A gazetteer name without its qualifiers: a parenthesis, what follows a comma, a
    trailing ' city' ('Seattle (Wa)' -> seattle, 'Cebu City' -> cebu)."""
    base = _fold(re.sub(r"\s*\(.*?\)", "", name)).split(",")[0].strip()
    shorts = {base, base.removesuffix(" city").strip()}
    return {s for s in shorts if s and s != _fold(name)}


@functools.lru_cache(maxsize=1)
def _short_index() -> dict[str, list[dict]]:
    """Folded short name -> gazetteer entries, for names that match no entry exactly."""
    by_name, _ = _gazetteer()
    index: dict[str, list[dict]] = {}
    for entries in by_name.values():
        for p in entries:
            for short in _short_names(p["name"]):
                index.setdefault(short, []).append(p)
            folded = _fold(p["name"])
            if folded != p["name"].lower():
                index.setdefault(folded, []).append(p)
    return index


def _km(a: dict, b: dict) -> float:
    """Geodesic distance between two gazetteer entries [km] (ambiguity test)."""
    _, d = inverse(a["lon"], a["lat"], b["lon"], b["lat"])
    return float(d) / 1000.0


def _choice_note(text: str, chosen: dict, cands: list[dict]) -> str:
    """What the plan says when `text` names several ports far apart ('' when it does not)."""
    others = sorted({f"{p['name']} {p.get('port') or '?'} ({p['lat']:.2f}, {p['lon']:.2f})"
                     for p in cands if _km(p, chosen) > _AMBIGUOUS_KM})
    if not others:
        return ""
    return (f"{text.strip()!r} names {len(others) + 1} ports in the gazetteer: chose "
            f"{chosen['name']} {chosen.get('port') or ''} ({chosen['lat']:.2f}, "
            f"{chosen['lon']:.2f}); the others: {'; '.join(others)} "
            "(give a UN/LOCODE or 'lat,lon' to choose another)")


@functools.lru_cache(maxsize=1)
def _gazetteer() -> tuple[dict[str, list[dict]], dict[str, dict]]:
    path = resources.files("searoute") / "data" / "ports.geojson"
    features = json.loads(path.read_text())["features"]
    by_name: dict[str, list[dict]] = {}
    by_code: dict[str, dict] = {}
    for f in features:
        p = dict(f["properties"])
        p["t"] = float(p.get("t") or 0.0)
        p["lon"], p["lat"] = f["geometry"]["coordinates"][:2]
        by_name.setdefault(p["name"].lower(), []).append(p)
        code = (p.get("port") or "").upper()
        code = p["port"] = LOCODE_FIXES.get((p["name"].lower(), code), code)
        if code and (code not in by_code or p.get("t", 0) > by_code[code].get("t", 0)):
            by_code[code] = p
    return by_name, by_code


def _rank(p: dict) -> tuple[float, int]:
    """Prefer main entries (t = 1) with the most connections."""
    return (float(p.get("t", 0.0)), len(p.get("to_cty", []) or []))


def lookup_port(text: str) -> Port:
    """Resolve a name, UN/LOCODE or 'lat,lon' to a position (not yet checked against land)."""
    query = text.strip()
    m = _LATLON.match(query)
    if m:
        lat, lon = float(m.group(1)), float(m.group(2))
        if not (-90.0 <= lat <= 90.0) or not (-180.0 <= lon <= 360.0):
            raise PortNotFoundError(
                f"coordinates {text!r} are out of range: expected 'lat,lon' with lat in "
                "-90..90 and lon in -180..360 degrees"
            )
        return Port(f"{lat:.4f},{lon:.4f}", "", lat, (lon + 180.0) % 360.0 - 180.0)
    by_name, by_code = _gazetteer()
    key = query.lower()
    compact = key.replace(" ", "")
    choice = ""
    if len(compact) == 5 and compact.isalnum() and compact.upper() in by_code:
        p = by_code[compact.upper()]
    else:
        key = ALIASES.get(key, ALIASES.get(_fold(key), key))
        short = _short_index().get(_fold(key), [])
        cands = by_name.get(key) or by_name.get(_fold(key)) or short
        if not cands:
            close = difflib.get_close_matches(key, list(by_name) + list(ALIASES), n=5,
                                              cutoff=0.75)
            close += sorted(n for n in by_name if n.startswith(key[:4]) and n not in close)
            close = close[:5]
            hint = f"; similar names: {', '.join(close)}" if close else ""
            raise PortNotFoundError(
                f"port {text!r} not found in the searoute gazetteer (use a port name, a "
                f"UN/LOCODE such as KRPUS, or 'lat,lon'){hint}"
            )
        p = max(cands, key=_rank)
        choice = _choice_note(text, p, cands + [q for q in short if q not in cands])
    code = p.get("port") or ""
    if code in RIVER_PORTS:
        channel, lat, lon = RIVER_PORTS[code]
        river = (f"{p['name']} lies up the {channel}: the plan starts/ends at its seaward end "
                 f"({lat:.2f}, {lon:.2f}); the river passage is pilotage and not planned")
        return Port(p["name"], code, lat, lon, note=_join_notes(choice, river),
                    berth_lat_deg=float(p["lat"]), berth_lon_deg=float(p["lon"]))
    return Port(p["name"], code, float(p["lat"]), float(p["lon"]), note=choice)


def _join_notes(*notes: str) -> str:
    """Several notes about one port as one warning."""
    return "; ".join(n for n in notes if n)


def snap_to_sea(port: Port, land: LandMask, max_snap_km: float = 25.0) -> Port:
    """Move a port on land to the nearest water sample within `max_snap_km`, else raise."""
    if not land.is_land(np.array([port.lon_deg]), np.array([port.lat_deg]))[0]:
        return port
    step_km = 0.5
    radii = np.arange(step_km, max_snap_km + 1e-9, step_km)
    az = np.radians(np.arange(0.0, 360.0, 7.5))
    rr, aa = np.meshgrid(radii, az, indexing="ij")
    dlat = rr * np.cos(aa) / 111.2
    dlon = rr * np.sin(aa) / (111.2 * max(np.cos(np.radians(port.lat_deg)), 0.05))
    lat = port.lat_deg + dlat.ravel()
    lon = port.lon_deg + dlon.ravel()
    wet = ~land.is_land(lon, lat)
    if not wet.any():
        raise PositionOnLandError(
            f"{port.name} ({port.lat_deg:.4f}, {port.lon_deg:.4f}) is on land and no "
            f"navigable water lies within {max_snap_km:g} km: give a position at sea"
        )
    k = int(np.flatnonzero(wet)[0])
    moved = float(rr.ravel()[k])
    snapped = (f"{port.name}: the gazetteer position is on land; moved {moved:g} km to the "
               "nearest navigable water" if moved > 2.0 and not port.is_river_port else "")
    note = _join_notes(port.note, snapped)
    return dataclasses.replace(port, lat_deg=float(lat[k]), lon_deg=float(lon[k]),
                               snapped_km=moved, note=note)


def resolve_port(text: str, land: LandMask, max_snap_km: float = 25.0) -> Port:
    """Look up `text` and make sure the position is at sea: snapped within
    `river_ends.SNAP_KM`; a gazetteer port farther from water the coastline resolves lies up
    a river or channel and is planned from its seaward end on the sea lane
    (`river_ends.seaward_end`), else snapped within `max_snap_km`."""
    port = lookup_port(text)
    if _LATLON.match(text.strip()) or port.is_river_port:
        return snap_to_sea(port, land, max_snap_km)
    try:
        snapped = snap_to_sea(port, land, max_snap_km)
    except PositionOnLandError as exc:
        river = _river_port(port, land, max_snap_km, beyond=True)
        if river is None:
            raise PositionOnLandError(
                f"{exc}; nor does the sea-lane network lead from it, within "
                f"{MAX_RIVER_NM:g} NM down a river, to water the coastline resolves (lakes and "
                "inland seas, the Great Lakes and the Caspian among them, are land in the "
                "GSHHG coastline used here): give the river's seaward end as 'lat,lon'") from None
        return river
    if snapped.snapped_km <= SNAP_KM:
        return snapped
    return _river_port(port, land, snapped.snapped_km) or snapped


def _river_port(port: Port, land: LandMask, gap_km: float, beyond: bool = False
                ) -> Port | None:
    """`port` planned from its river's seaward end on the sea lane (None when none is
    found); `gap_km`: how far the nearest resolved water is (`beyond`: none within it)."""
    end = seaward_end(port.lat_deg, port.lon_deg, land)
    if end is None:
        return None
    note = river_note(port.name, port.lat_deg, port.lon_deg, end, gap_km, beyond)
    return Port(port.name, port.locode, end.lat_deg, end.lon_deg,
                note=_join_notes(port.note, note), berth_lat_deg=port.lat_deg,
                berth_lon_deg=port.lon_deg)
