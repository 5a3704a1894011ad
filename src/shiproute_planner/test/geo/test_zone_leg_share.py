"""A leg's length inside a zone against an independent reference (pyproj geodesic points every
~0.02 NM tested with shapely), including a leg that clips a zone's corner between the points
its evaluation samples: a hard zone cannot be cut unseen."""

from __future__ import annotations

import numpy as np
import pyproj
import shapely
from shiproute_core.units import M_PER_NM
from shiproute_planner.geo.zones import Zone, Zones, gc_samples

BOX = shapely.Polygon([(-8.0, 45.5), (-7.0, 45.5), (-7.0, 46.5), (-8.0, 46.5)])
GEOD = pyproj.Geod(ellps="WGS84")


def _reference_nm(lon0: float, lat0: float, lon1: float, lat1: float) -> tuple[float, float]:
    """(NM inside BOX, leg NM) from geodesic points every ~0.02 NM."""
    _, _, leg_m = GEOD.inv(lon0, lat0, lon1, lat1)
    n = int(leg_m / (0.02 * M_PER_NM))
    pts = np.array(GEOD.npts(lon0, lat0, lon1, lat1, n))
    inside = shapely.contains_xy(BOX, pts[:, 0], pts[:, 1]).sum()
    return inside * leg_m / (n + 1) / M_PER_NM, leg_m / M_PER_NM


def test_a_corner_clip_between_samples_counts_its_length():
    leg = (-8.63, 46.17, -7.43, 46.77)  # ~61 NM, across the box's north-west corner
    samples_lon, samples_lat = gc_samples(*(np.array([v]) for v in leg), 16)
    # premise: none of the 17 points a leg is evaluated at lies in the box
    assert not shapely.contains_xy(BOX, samples_lon, samples_lat).any()
    inside_nm, leg_nm = _reference_nm(*leg)
    assert 1.0 < inside_nm < 3.0
    share = Zones((Zone("exercise", BOX),)).leg_inside(*(np.array([v]) for v in leg))
    assert abs(share[0, 0] * leg_nm - inside_nm) < 0.1


def test_legs_across_and_outside_the_zone():
    legs = np.array([(-10.0, 46.0, -5.0, 46.0),  # straight across: ~41 NM inside
                     (-10.0, 47.0, -5.0, 47.0)])  # north of it: none
    share = Zones((Zone("exercise", BOX),)).leg_inside(*legs.T)
    for k, leg in enumerate(legs):
        inside_nm, leg_nm = _reference_nm(*leg)
        assert abs(share[0, k] * leg_nm - inside_nm) < 0.1
    assert share[0, 1] == 0.0
