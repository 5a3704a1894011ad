"""The clearance rule's sea-area types against real waters (GSHHG full resolution; distances by
pyproj and shapely on the same polygons, points every ~0.05 NM): an open-sea leg passing an
isolated island within 2 NM is penalised by the search's walk and one keeping 2 NM is not; a
leg through a channel narrower than twice the open-sea clearance (Uraga Suido) that keeps off
land passes; a leg across the peninsula beside it does not."""

from __future__ import annotations

import numpy as np
import pytest
from shiproute_core.units import M_PER_NM
from shiproute_planner.route.clearance import NARROW_MARGIN_NM, TIGHT_ROOM_NM, ClearanceRule
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
