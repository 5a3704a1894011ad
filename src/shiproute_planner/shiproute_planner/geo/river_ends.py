"""The seaward end of a port up a river or channel the coastline does not resolve, found along
the sea lane: for ports without an entry in `port_aliases.RIVER_PORTS`.

A gazetteer port whose position lies farther than `SNAP_KM` from water the coastline
resolves (Seville, Rosario, Nanjing, Longview, Beaumont, ...) sits on a river or channel
narrower than the data. The `searoute` lane network follows such rivers, and a river leads
out one way whatever the destination: the lane from the port towards the nearest
`OCEAN_HUBS` point leaves by it. Walking that lane from the port, the seaward end is the
first sample (every `SAMPLE_NM`) from which the lane runs on in water of the full-resolution
coastline for `CLEAR_RUN_NM`, with water `WIDTH_NM` round it in every direction: there the
coastal passages (0.25-0.05 NM grids) can start. The river passage from the berth to it is
pilotage, timed as for the table's river ports (`river_passages`); one longer than
`MAX_RIVER_NM`, or from a berth the lane network does not reach, is not guessed.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from shiproute_core.geodesy import M_PER_NM, densify_track, direct, inverse

from .landmask import LandMask
from .sea_lanes import sea_lane_between

SNAP_KM = 5.0  # a port this close to resolved water is snapped to it (harbour basins)
SAMPLE_NM = 0.25  # lane sample spacing: the route check's
CLEAR_RUN_NM = 5.0  # the lane runs on in water this far from the seaward end
WIDTH_NM = 0.5  # water round the seaward end in 8 directions: room for a passage's grid
# the longest river passage taken without a table entry [NM], berth to seaward end: the
# rivers found so far are 10-150 NM (Savannah 14, Seville 50, Rosario 135); beyond, the lane
# runs through inland waterways whose locks and depths nothing here knows (Turkmenbasy's,
# on the Caspian, leads 977 NM up the Volga and through the Volga-Don canal)
MAX_RIVER_NM = 300.0
# the lane network's nearest node to a berth farther than this: the network does not reach
# the port (Wuhan's nearest node is the Yangtze's mouth, 529 km away; Iquitos's is on the
# Pacific coast, over the Andes), and the lane says nothing of its river
LANE_START_KM = 100.0
# mid-ocean points (lat, lon): the lane to the nearest one leaves a river the way every lane
# does (only its first stretch is used)
OCEAN_HUBS: tuple[tuple[float, float], ...] = (
    (40.0, -40.0), (10.0, -35.0), (-30.0, -20.0), (30.0, -150.0), (0.0, -120.0),
    (-35.0, -110.0), (30.0, 160.0), (-10.0, 75.0), (-40.0, 100.0), (10.0, 65.0),
    (15.0, 115.0), (-20.0, 165.0), (70.0, 0.0),
)


@dataclass(frozen=True)
class SeawardEnd:
    """Where the sea lane from a berth reaches water the coastline resolves."""

    lat_deg: float
    lon_deg: float
    along_nm: float  # lane distance from the lane's first point to the seaward end


def nearest_hub(lat_deg: float, lon_deg: float) -> tuple[float, float]:
    """The `OCEAN_HUBS` point (lat, lon) nearest to a position (great circle)."""
    lats = np.array([h[0] for h in OCEAN_HUBS])
    lons = np.array([h[1] for h in OCEAN_HUBS])
    _, dist = inverse(np.full(lats.size, lon_deg), np.full(lats.size, lat_deg), lons, lats)
    return OCEAN_HUBS[int(np.argmin(dist))]


def seaward_end(lat_deg: float, lon_deg: float, land: LandMask) -> SeawardEnd | None:
    """The seaward end of the river or channel from a berth (None when the lane network finds
    no way to the ocean, its nearest node lies farther than `LANE_START_KM`, or no water the
    coastline resolves lies within `MAX_RIVER_NM` of the berth along it): off land in `land`
    (the search's mask) and in the full-resolution coastline."""
    hub = nearest_hub(lat_deg, lon_deg)
    lane = sea_lane_between(lon_deg, lat_deg, hub[1], hub[0])
    if lane is None or len(lane) < 2:
        return None
    _, start_m = inverse(lon_deg, lat_deg, float(lane[0, 0]), float(lane[0, 1]))
    if float(start_m) > LANE_START_KM * 1000.0:
        return None
    hop_nm = float(start_m) / M_PER_NM
    lon, lat = densify_track(np.unwrap(lane[:, 0], period=360.0), lane[:, 1],
                             SAMPLE_NM * M_PER_NM)
    limit = min(lon.size, int(max(MAX_RIVER_NM - hop_nm, 0.0) / SAMPLE_NM) + 1)
    lon, lat = np.asarray(lon[:limit]), np.asarray(lat[:limit])
    wet = _water(lon, lat, land)
    run = round(CLEAR_RUN_NM / SAMPLE_NM)
    # samples k with k..k+run all in water: a run of `run + 1` wet samples starts at k
    ok = np.convolve(wet.astype(np.int64), np.ones(run + 1, dtype=np.int64), "valid") == run + 1
    for k in np.flatnonzero(ok).tolist():
        if _wide(float(lon[k]), float(lat[k]), land):
            return SeawardEnd(float(lat[k]), float((lon[k] + 180.0) % 360.0 - 180.0),
                              k * SAMPLE_NM)
    return None


def _wide(lon_deg: float, lat_deg: float, land: LandMask) -> bool:
    """True when the points `WIDTH_NM` from a position in 8 directions are all water (full
    resolution and the search's mask)."""
    az = np.arange(0.0, 360.0, 45.0)
    lon, lat = direct(np.full(az.size, lon_deg), np.full(az.size, lat_deg), az,
                      np.full(az.size, WIDTH_NM * M_PER_NM))
    lon, lat = np.asarray(lon), np.asarray(lat)
    return bool(_water(lon, lat, land).all())


def _water(lon: np.ndarray, lat: np.ndarray, land: LandMask) -> np.ndarray:
    """True where a point is water in both the search's mask and the full-resolution
    coastline (the route check's)."""
    from .full_land import final_land

    return ~final_land().contains(lon, lat) & ~land.is_land(lon, lat)


def river_note(name: str, lat_deg: float, lon_deg: float, end: SeawardEnd, gap_km: float,
               beyond: bool = False) -> str:
    """What the plan says about a port planned from a seaward end found on the lane;
    `gap_km`: how far the nearest resolved water is (`beyond`: none within it)."""
    gap = f"more than {gap_km:g} km" if beyond else f"{gap_km:.0f} km"
    return (f"{name}: its gazetteer position ({lat_deg:.3f}, {lon_deg:.3f}) lies {gap} from "
            "water the GSHHG full-resolution coastline resolves (a berth up a river or channel "
            "narrower than the data, or a position inland): the plan starts/ends at the "
            f"seaward end, where the sea lane from it first reaches resolved water "
            f"({end.lat_deg:.3f}, {end.lon_deg:.3f}); the river passage is pilotage and not "
            "planned (its length is the sea lane's, joined to the berth by a straight line "
            "where the lane network does not reach it)")
