"""User-given coastal passages (`plan --approach FILE`): an RTZ or GeoJSON route from a port
to open sea or from sea to a port, sailed as given instead of the computed approach and
checked like every other leg (the route check lists what it finds)."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np
from shiproute_core.geodesy import inverse, unwrap_near
from shiproute_core.units import M_PER_NM

from ..geo.ports import Port
from ..io.route_read import read_route
from .approach import Approach

MATCH_NM = 10.0  # a given passage belongs to a port when one of its ends is this close


def load_approaches(paths: Sequence[str | Path]) -> list[Approach]:
    """Polylines of the given route files (errors name the file)."""
    out = []
    for p in paths:
        track = read_route(p)
        out.append(Approach(np.asarray(track.lon_deg, dtype=float),
                            np.asarray(track.lat_deg, dtype=float)))
    return out


def _near(lon: float, lat: float, port: Port) -> bool:
    _, d = inverse(lon, lat, port.lon_deg, port.lat_deg)
    return float(d) / M_PER_NM <= MATCH_NM


def approaches_at(given: Sequence[Approach], dep: Port, arr: Port
                  ) -> tuple[Approach | None, Approach | None]:
    """(departure, arrival) approach among `given` for a leg dep -> arr: one starting (or,
    reversed, ending) at the departure port, one ending (or starting) at the arrival port;
    the port end is replaced by the port's own position."""
    dep_ap = arr_ap = None
    for ap in given:
        lon, lat = ap.lon_deg, ap.lat_deg
        for fwd_lon, fwd_lat in ((lon, lat), (lon[::-1], lat[::-1])):
            if dep_ap is None and _near(fwd_lon[0], fwd_lat[0], dep):
                dep_ap = _anchored(fwd_lon, fwd_lat, dep, first=True)
                break
            if arr_ap is None and _near(fwd_lon[-1], fwd_lat[-1], arr):
                arr_ap = _anchored(fwd_lon, fwd_lat, arr, first=False)
                break
    return dep_ap, arr_ap


def _anchored(lon: np.ndarray, lat: np.ndarray, port: Port, first: bool) -> Approach:
    lon, lat = lon.copy(), lat.copy()
    k = 0 if first else -1
    lon[k], lat[k] = port.lon_deg, port.lat_deg
    lon = np.unwrap(lon, period=360.0)
    shift = unwrap_near(port.lon_deg, lon[k]) - port.lon_deg
    return Approach(lon - shift, lat)
