"""Level-1 distance tiles: a lower bound of the geodesic distance to the full-resolution
coastline (pyproj/shapely on the same polygons), not much looser than a fine cell, 0 on land."""

from __future__ import annotations

import numpy as np
import pytest
from shiproute_core.units import M_PER_NM
from shiproute_planner.geo.fine_distance import CAP_NM, FINE_PER_TILE, TILE_DEG, FineDistance

SPHERE_SLACK = 60.0 / 59.6  # sphere arcminutes vs WGS 84 geodesic NM (see test_coast_distance)


@pytest.fixture(scope="module")
def final():
    from shiproute_planner.geo.full_land import final_land

    return final_land()


def _true_distance_nm(final, lon: float, lat: float) -> float:
    """Geodesic distance [NM] from a point to the nearest land of the final coastline (0 on
    land), in an azimuthal equidistant projection centred on the point."""
    import pyproj
    import shapely

    half_lat = 0.3
    half_lon = half_lat / np.cos(np.radians(abs(lat) + half_lat))
    parts = final.tiles.land_near(lon - half_lon, lat - half_lat, lon + half_lon, lat + half_lat)
    if not parts:
        return np.inf
    aeqd = pyproj.Transformer.from_crs(
        "EPSG:4326", f"+proj=aeqd +lat_0={lat} +lon_0={lon} +ellps=WGS84", always_xy=True)
    land = shapely.transform(np.array(parts, dtype=object),
                             lambda xy: np.column_stack(aeqd.transform(xy[:, 0], xy[:, 1])))
    return float(np.min(shapely.distance(shapely.Point(0.0, 0.0), land))) / M_PER_NM


# Isles of Scilly, the Bosphorus, the Zhoushan islets, Sognefjord, Juan de Fuca
@pytest.mark.parametrize("centre", [(-6.32, 49.93), (29.05, 41.12), (122.25, 30.0),
                                    (5.6, 61.1), (-123.6, 48.3)])
def test_level1_bounds_the_geodesic_distance_to_the_full_coastline(final, centre, tmp_path):
    fine = FineDistance(final.tiles.land_near, final.contains, tmp_path / "tiles.npz")
    rng = np.random.default_rng(round(1000 * centre[0]) % 2**32)
    lon = centre[0] + rng.uniform(-0.25, 0.25, 120)
    lat = centre[1] + rng.uniform(-0.2, 0.2, 120)
    bound = fine.distance_nm(lon, lat)
    on_land = final.contains(lon, lat)
    assert np.all(bound[on_land] == 0.0)
    fine_nm = TILE_DEG / FINE_PER_TILE * 60.0
    looser = 0
    for k in range(lon.size):
        true_nm = _true_distance_nm(final, lon[k], lat[k])
        assert bound[k] <= true_nm * SPHERE_SLACK + 1e-9, (lon[k], lat[k], bound[k], true_nm)
        # looser by at most a cell diagonal, the coastline band (1.5 cells), the longitude
        # shrink over the padded tile (< 1 %) and the step of the stored values
        slack = 2.5 * np.hypot(fine_nm, fine_nm) + 0.01 * true_nm + 0.05
        assert min(true_nm, CAP_NM) - bound[k] <= slack, (lon[k], lat[k], bound[k], true_nm)
        looser += true_nm < CAP_NM
    assert looser >= 20  # the sample reaches the coast
    # saved and loaded: the same tiles
    fine.save()
    again = FineDistance(final.tiles.land_near, final.contains, tmp_path / "tiles.npz")
    assert np.array_equal(again.distance_nm(lon, lat), bound)


def test_level1_tiles_meet_across_the_antimeridian(final, tmp_path):
    fine = FineDistance(final.tiles.land_near, final.contains, tmp_path / "tiles.npz")
    lat = np.linspace(51.2, 52.2, 400)
    east = fine.distance_nm(np.full(lat.size, 179.9999), lat)
    west = fine.distance_nm(np.full(lat.size, -179.9999), lat)
    # the same place a few metres apart: bounds differ by at most a cell and a bit
    assert np.max(np.abs(east - west)) <= 2 * TILE_DEG / FINE_PER_TILE * 60.0 + 0.05


def test_saves_append_parts_that_load_as_one_and_merge(final, tmp_path, monkeypatch):
    # each save writes only the tiles built since the last one; a later process reads the
    # cache file and every part, and merges the parts into the file once there are many
    from shiproute_planner.geo import fine_distance as fd

    path = tmp_path / "tiles.npz"
    fine = FineDistance(final.tiles.land_near, final.contains, path)
    lon = np.array([-6.32, 29.05, 122.25])  # Scilly, the Bosphorus, Zhoushan: three tiles
    lat = np.array([49.93, 41.12, 30.0])
    for k in range(3):  # one more tile per save
        values = fine.distance_nm(lon[:k + 1], lat[:k + 1])
        fine.save()
    fine.save()  # nothing new: no part
    parts = sorted(tmp_path.glob("tiles_part*.npz"))
    assert len(parts) == 3 and not path.exists()
    assert sum(np.load(p)["keys"].size for p in parts) == 3  # each tile saved once
    again = FineDistance(final.tiles.land_near, final.contains, path)
    assert again.count == 3
    assert np.array_equal(again.distance_nm(lon, lat), values)
    assert again.add(np.flatnonzero(again.slots.ravel() >= 0)) == 0  # nothing rebuilt
    monkeypatch.setattr(fd, "MAX_PARTS", 3)
    merged = FineDistance(final.tiles.land_near, final.contains, path)
    assert path.exists() and not list(tmp_path.glob("tiles_part*.npz"))
    last = FineDistance(final.tiles.land_near, final.contains, path)
    assert merged.count == last.count == 3
    assert np.array_equal(last.distance_nm(lon, lat), values)
