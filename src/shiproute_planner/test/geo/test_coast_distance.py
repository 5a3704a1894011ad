"""The level-0 distance to the coast: a lower bound of the geodesic distance (pyproj/shapely),
not much looser than a cell diagonal, signed by land and sea."""

from __future__ import annotations

import numpy as np
import pytest
from shiproute_core.units import M_PER_NM
from shiproute_planner.geo.coast_distance import NM_PER_DEG, UNIT_NM, coast_distance
from shiproute_planner.geo.raster import COAST, LAND, SEA

# one sphere arcminute vs the WGS 84 geodesic: a meridian degree is >= 59.7 NM at the equator
SPHERE_SLACK = 60.0 / 59.6


def _true_distance_nm(land_mask, lon: float, lat: float) -> float:
    """Geodesic distance [NM] from a point to the coastline of `land_mask`'s polygons
    (azimuthal equidistant projection centred on the point: distances from it are exact):
    the nearest land seen from the sea, and the nearest sea seen from land, lie on the rings."""
    import pyproj
    import shapely
    from shiproute_planner.geo.nav_grid import land_in_box

    half_lon = 2.0 / np.cos(np.radians(abs(lat) + 2.0))
    parts = land_in_box(land_mask.polygons, lon - half_lon, lat - 2.0, lon + half_lon,
                        lat + 2.0, False)
    if not parts:
        return np.inf
    aeqd = pyproj.Transformer.from_crs(
        "EPSG:4326", f"+proj=aeqd +lat_0={lat} +lon_0={lon} +ellps=WGS84", always_xy=True)
    rings = shapely.transform(shapely.boundary(np.array(parts, dtype=object)),
                              lambda xy: np.column_stack(aeqd.transform(xy[:, 0], xy[:, 1])))
    return float(np.min(shapely.distance(shapely.Point(0.0, 0.0), rings))) / M_PER_NM


@pytest.mark.parametrize("centre", [(-6.3, 49.9), (5.0, 60.5), (140.5, 41.5), (25.5, 37.5),
                                    (-123.5, 48.5)])
def test_level0_bounds_the_geodesic_distance_to_the_coast(land_mask, centre):
    rng = np.random.default_rng(abs(hash(centre)) % 2**32)
    dist = np.asarray(land_mask.coast_distance)
    raster = np.asarray(land_mask.raster)
    cell = land_mask.cell_deg
    lon = centre[0] + rng.uniform(-1.5, 1.5, 60)
    lat = centre[1] + rng.uniform(-1.0, 1.0, 60)
    i = ((lat + 90.0) / cell).astype(int)
    j = ((lon + 180.0) / cell).astype(int)
    bound_nm = dist[i, j] * UNIT_NM
    cls = raster[i, j]
    on_land = land_mask.is_land(lon, lat)
    assert np.all(on_land[cls == LAND]) and not np.any(on_land[cls == SEA])
    assert np.all(bound_nm[cls == COAST] == 0.0)
    assert np.all(bound_nm[cls == SEA] >= 0.0) and np.all(bound_nm[cls == LAND] <= 0.0)
    checked = 0
    for k in np.flatnonzero(cls != COAST):
        true_nm = _true_distance_nm(land_mask, lon[k], lat[k])
        assert abs(bound_nm[k]) <= true_nm * SPHERE_SLACK + 1e-9, (lon[k], lat[k])
        if true_nm < 40.0:
            # looser by at most: a cell diagonal (any point to any point), one cell of the
            # raster's dilated coast band (1.5 diagonals) and the band's longitude shrink
            # (cos of the band's pole-side edge plus the reach vs the point's latitude)
            diag_nm = np.hypot(1.0, 1.0) * cell * NM_PER_DEG
            shrink = np.cos(np.radians(min(abs(centre[1]) + 12.0, 89.0))) / np.cos(
                np.radians(abs(lat[k])))
            assert true_nm - abs(bound_nm[k]) <= 2.5 * diag_nm + (1 - shrink) * true_nm + 0.2
            checked += 1
    assert checked >= 10


def test_level0_wraps_in_longitude_and_caps():
    cell = 1.0
    raster = np.zeros((180, 360), dtype=np.uint8)
    raster[90, 0] = COAST  # one coastal cell on the equator at 180 W .. 179 W
    d = coast_distance(raster, cell, cap_nm=300.0, band_deg=5.0) * UNIT_NM
    assert d[90, 356] == d[90, 4]  # four cells west across the antimeridian, four east
    # four cells east on the equator: the band's shrink is cos(5 + 5 + 1 deg); any point to
    # any point of the two cells (a diagonal), and the coastline lies half a cell inside
    # the coastal band (its cells' neighbours are coastal too)
    shrink = np.cos(np.radians(11.0))
    expect = 4 * 60.0 * shrink - np.hypot(60.0, 60.0 * shrink) + 30.0 * shrink
    assert d[90, 4] == pytest.approx(np.floor(expect / UNIT_NM) * UNIT_NM, abs=1e-6)
    assert d[10, 180] == pytest.approx(300.0)  # far from the coast: the cap
    raster[:] = LAND
    raster[90, 0] = COAST
    assert coast_distance(raster, cell)[90, 5] < 0  # inland: negative
