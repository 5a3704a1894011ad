"""The clearance walk against geodesic distances to the full-resolution coastline (pyproj and
shapely on the same polygons, points every ~0.05 NM): a leg it calls clear keeps its
clearance everywhere (less the walk's eps), a leg it flags comes close to breaking it."""

from __future__ import annotations

import numpy as np
import pytest
from shiproute_core.units import M_PER_NM
from shiproute_planner.route.clearance import EPS_NM, ClearanceRule

LOOSENESS_NM = 0.7  # level 1's looseness (a fine diagonal, the coastline band, one step)


@pytest.fixture(scope="module")
def walk_inputs():
    from shiproute_planner.geo.fine_distance import default_fine_distance
    from shiproute_planner.geo.full_land import final_land
    from shiproute_planner.geo.narrow_water import default_room
    from shiproute_planner.route.fast_eval import coarse_land

    final = final_land()
    coarse, clear, coarse_deg = coarse_land(final.mask)
    return final, default_fine_distance(), coarse, clear, coarse_deg, np.asarray(default_room())


def _walk(walk_inputs, lon0, lat0, lon1, lat1, rule, ends_lonlat):
    from shiproute_planner.route import _land_walk as lw

    final, fine, coarse, clear, coarse_deg, room = walk_inputs
    ends = np.array([*lw.unit_vector(ends_lonlat[1], ends_lonlat[0]),
                     *lw.unit_vector(ends_lonlat[3], ends_lonlat[2])])
    got = np.full(lon0.size, -1, dtype=np.int64)
    todo = np.arange(lon0.size)
    for _ in range(200):  # as the evaluator does: build the tiles met, rescan those legs
        missing = np.empty(64, dtype=np.int64)  # small: exercises the full-buffer path
        part = np.empty(todo.size, dtype=np.int64)
        tight = np.zeros(todo.size, dtype=np.int64)
        # measured everywhere (the check's walk): the search leaves tight water to others
        n = lw.clearance_walk(lon0[todo], lat0[todo], lon1[todo], lat1[todo], coarse, clear,
                              coarse_deg, np.asarray(final.mask.coast_distance),
                              final.mask.cell_deg, 0.05, fine.slots, fine.grids, ends,
                              rule.kernel_array(search=False), room, missing, part, tight)
        got[todo] = part
        fine.add(missing[:n])
        todo = todo[part < 0]
        if not todo.size:
            return got
    raise AssertionError("tiles never all built")


def _dense_truth(final, room, lon0, lat0, lon1, lat1, rule, ends_lonlat):
    """(true distance to land [NM], clearance needed [NM]) at points ~0.05 NM apart; the
    sea-area type (narrow water) is the room raster's at each point, an input of the rule."""
    import pyproj
    import shapely
    from shiproute_planner.geo.narrow_water import UNIT_NM as ROOM_UNIT_NM
    from shiproute_planner.route.clearance import NARROW_MARGIN_NM

    geod = pyproj.Geod(ellps="WGS84")
    _, _, length_m = geod.inv(lon0, lat0, lon1, lat1)
    n = max(2, int(length_m / M_PER_NM / 0.05) + 1)
    pts = np.array(geod.npts(lon0, lat0, lon1, lat1, n - 2))
    pts = np.vstack([[lon0, lat0], pts.reshape(-1, 2), [lon1, lat1]])
    c_lon, c_lat = 0.5 * (lon0 + lon1), 0.5 * (lat0 + lat1)
    aeqd = pyproj.Transformer.from_crs(
        "EPSG:4326", f"+proj=aeqd +lat_0={c_lat} +lon_0={c_lon} +ellps=WGS84", always_xy=True)
    half = 0.4
    parts = final.tiles.land_near(min(lon0, lon1) - half / np.cos(np.radians(c_lat)),
                                  min(lat0, lat1) - half,
                                  max(lon0, lon1) + half / np.cos(np.radians(c_lat)),
                                  max(lat0, lat1) + half)
    x, y = aeqd.transform(pts[:, 0], pts[:, 1])
    if parts:
        land = shapely.union_all(shapely.transform(
            np.array(parts, dtype=object),
            lambda xy: np.column_stack(aeqd.transform(xy[:, 0], xy[:, 1]))))
        dist = shapely.distance(shapely.points(x, y), land) / M_PER_NM
    else:
        dist = np.full(x.size, np.inf)
    end_nm = np.full(x.size, np.inf)
    for e_lon, e_lat in (ends_lonlat[:2], ends_lonlat[2:]):
        _, _, d_m = geod.inv(pts[:, 0], pts[:, 1], np.full(x.size, e_lon),
                             np.full(x.size, e_lat))
        end_nm = np.minimum(end_nm, d_m / M_PER_NM)
    need = np.where(end_nm <= rule.free_radius_nm, 0.0,
                    np.where(end_nm <= rule.approach_zone_nm, rule.approach_nm,
                             rule.open_sea_nm))
    cell = final.mask.cell_deg
    i = np.clip(((pts[:, 1] + 90.0) // cell).astype(int), 0, room.shape[0] - 1)
    j = np.clip((((pts[:, 0] + 180.0) % 360.0) // cell).astype(int), 0, room.shape[1] - 1)
    narrow = room[i, j] * ROOM_UNIT_NM < rule.open_sea_nm + NARROW_MARGIN_NM
    return dist, np.where(narrow, np.minimum(need, rule.approach_nm), need)


# the Isles of Scilly, the Zhoushan islets, Juan de Fuca; the Bosphorus (0.4-2 NM wide)
# with the clearance of a narrow strait
@pytest.mark.parametrize(("centre", "open_sea_nm"), [
    ((-6.35, 49.92), 2.0), ((29.05, 41.1), 0.2), ((122.3, 30.0), 2.0), ((-123.6, 48.3), 2.0)])
def test_walk_keeps_the_clearance_it_reports(walk_inputs, centre, open_sea_nm):
    final = walk_inputs[0]
    rng = np.random.default_rng(round(100 * centre[1]))
    rule = ClearanceRule(open_sea_nm, min(0.5, open_sea_nm), 10.0)
    lon0 = centre[0] + rng.uniform(-0.3, 0.3, 60)
    lat0 = centre[1] + rng.uniform(-0.2, 0.2, 60)
    course, length = rng.uniform(0.0, 2 * np.pi, 60), rng.uniform(0.02, 0.15, 60)
    lon1 = lon0 + length * np.sin(course) / np.cos(np.radians(lat0))
    lat1 = lat0 + length * np.cos(course)
    # half the legs start at a span end (approach rule), half are open sea (ends far away)
    got = np.empty(lon0.size, dtype=np.int64)
    ends_of = []
    for half in (slice(0, 30), slice(30, 60)):
        ends = ((lon0[half.start], lat0[half.start], lon1[half.start], lat1[half.start])
                if half.start == 0 else (0.0, 0.0, 0.0, 0.5))
        ends_of += [ends] * 30
        got[half] = _walk(walk_inputs, lon0[half], lat0[half], lon1[half], lat1[half], rule,
                          ends)
    assert np.all(got >= 0)
    clear, flagged = 0, 0
    for k in range(lon0.size):
        dist, need = _dense_truth(final, walk_inputs[5], lon0[k], lat0[k], lon1[k], lat1[k],
                                  rule, ends_of[k])
        if got[k] == 0:
            # 0.05 NM between the dense points: a point between them is that much closer
            assert np.all(dist >= need - EPS_NM - 0.03), (k, float(np.min(dist - need)))
            clear += 1
        else:
            assert np.any(dist < need + LOOSENESS_NM), (k, float(np.min(dist - need)))
            flagged += 1
    assert clear >= 3 and flagged >= 3  # both kinds of legs


def test_walk_grades_a_leg_by_how_much_of_it_crosses_land(walk_inputs):
    # eastward along 50 N from the Atlantic into France: the longer the leg runs over land,
    # the larger the count
    rule = ClearanceRule(0.0, 0.0, 0.0)
    lon0 = np.full(4, -6.0)
    lat = np.full(4, 48.0)
    lon1 = np.array([-4.0, -2.0, 2.0, 6.0])
    got = _walk(walk_inputs, lon0, lat, lon1, lat, rule, (0.0, 0.0, 0.0, 0.5))
    assert got[0] > 0 and np.all(np.diff(got) > 0)


def test_walk_beyond_its_level1_latitude_reads_no_tile_and_never_calls_a_close_leg_clear(
        walk_inputs, tmp_path):
    # legs round Svalbard's west coast (78 N) walked with level 1 limited to 70 N and no tile
    # built: nothing is asked of level 1, and a leg called clear keeps the clearance by
    # geodesic distances to the full-resolution coast; a leg level 0 cannot clear is flagged
    from shiproute_planner.geo.fine_distance import FineDistance
    from shiproute_planner.route import _land_walk as lw

    final, _, coarse, clear, coarse_deg, room = walk_inputs
    empty = FineDistance(final.tiles.land_near, final.contains, tmp_path / "none.npz")
    rng = np.random.default_rng(78)
    rule = ClearanceRule(2.0, 0.5, 10.0)
    lon0 = 12.5 + rng.uniform(-1.0, 1.0, 60)
    lat0 = 78.3 + rng.uniform(-0.3, 0.3, 60)
    course, length = rng.uniform(0.0, 2 * np.pi, 60), rng.uniform(0.02, 0.3, 60)
    lon1 = lon0 + length * np.sin(course) / np.cos(np.radians(lat0))
    lat1 = lat0 + length * np.cos(course)
    ends_lonlat = (0.0, 0.0, 0.0, 0.5)  # open sea: the span ends are far away
    ends = np.array([*lw.unit_vector(0.0, 0.0), *lw.unit_vector(0.5, 0.0)])
    missing = np.empty(64, dtype=np.int64)
    got = np.empty(lon0.size, dtype=np.int64)
    n = lw.clearance_walk(lon0, lat0, lon1, lat1, coarse, clear, coarse_deg,
                          np.asarray(final.mask.coast_distance), final.mask.cell_deg, 0.05,
                          empty.slots, empty.grids, ends,
                          rule.kernel_array(search=False, level1_lat_deg=70.0), room, missing,
                          got, np.zeros(lon0.size, dtype=np.int64))
    assert n == 0 and np.all(got >= 0)
    clear_legs, flagged = 0, 0
    for k in range(lon0.size):
        dist, need = _dense_truth(final, room, lon0[k], lat0[k], lon1[k], lat1[k], rule,
                                  ends_lonlat)
        if got[k] == 0:
            assert np.all(dist >= need - EPS_NM - 0.03), (k, float(np.min(dist - need)))
            clear_legs += 1
        else:
            flagged += 1
            if np.all(dist > need + 6.0):  # level 0 (0.05-deg cells) decides this far out
                raise AssertionError((k, float(np.min(dist - need))))
    assert clear_legs >= 3 and flagged >= 3


def test_points_within_the_cell_inside_distance_share_the_cell():
    # destinations on the sphere (pyproj, spherical earth) from random points in 0.05-deg
    # cells, in random directions, up to the distance the walk jumps within a cell
    import pyproj
    from shiproute_planner.route._land_walk import cell_inside_nm

    cell = 0.05
    sphere = pyproj.Geod(a=6371008.8, b=6371008.8)
    nm_m = 2 * np.pi * 6371008.8 / 360.0 / 60.0  # 1 NM = 1 arcminute on this sphere
    rng = np.random.default_rng(5)
    lat = rng.uniform(-80.0, 80.0, 400)
    lon = rng.uniform(-179.9, 179.9, 400)
    i = np.floor((lat + 90.0) / cell).astype(int)
    j = np.floor((lon + 180.0) / cell).astype(int)
    inside = np.array([cell_inside_nm(la, lo, a, b, cell)
                       for la, lo, a, b in zip(lat, lon, i, j, strict=True)])
    for _ in range(8):
        lon1, lat1, _ = sphere.fwd(lon, lat, rng.uniform(0.0, 360.0, lat.size),
                                   inside * nm_m * rng.uniform(0.9, 1.0, lat.size))
        assert np.array_equal(np.floor((lat1 + 90.0) / cell).astype(int), i)
        assert np.array_equal(np.floor((lon1 + 180.0) / cell).astype(int), j)
    # not vacuous: at a cell's centre on the equator the distance is half a cell
    assert abs(cell_inside_nm(0.025, 0.025, 1800, 3600, cell) - 0.5 * cell * 60.0) < 0.01


def test_search_walk_counts_a_leg_across_a_continent_as_land(walk_inputs):
    # across central Mexico (inland cells have no room, as tight water has none): the search
    # walk counts the land itself instead of leaving it to the intermediate coastline
    from shiproute_planner.route import _land_walk as lw

    final, fine, coarse, clear, coarse_deg, room = walk_inputs
    lon0, lat0, lon1, lat1 = (np.array([v]) for v in (-103.0, 21.0, -99.5, 20.0))
    assert final.contains(np.array([-101.25]), np.array([20.5]))[0]  # the middle is on land
    ends = np.array([*lw.unit_vector(0.0, 0.0), *lw.unit_vector(0.5, 0.0)])
    got, tight = np.full(1, -1, dtype=np.int64), np.zeros(1, dtype=np.int64)
    for _ in range(20):
        missing = np.empty(256, dtype=np.int64)
        n = lw.clearance_walk(lon0, lat0, lon1, lat1, coarse, clear, coarse_deg,
                              np.asarray(final.mask.coast_distance), final.mask.cell_deg, 0.05,
                              fine.slots, fine.grids, ends,
                              ClearanceRule(0.0, 0.5, 10.0).kernel_array(search=True), room,
                              missing, got, tight)
        if got[0] >= 0:
            break
        fine.add(missing[:n])
    assert got[0] > 0


def test_exact_tight_test_counts_the_polygon_points_every_quarter_nm(walk_inputs):
    # the exact evaluator's tight-water test against brute force: each segment densified on
    # its own (geodesic points every 0.25 NM, both ends) and its points tested one by one on
    # the full-resolution polygons; round Kanmon and across the antimeridian (Fiji)
    from shiproute_core.geodesy import densify_track
    from shiproute_planner.route.land_repair import STEP_M
    from shiproute_planner.route.land_walk import LandWalk

    final = walk_inputs[0]
    rng = np.random.default_rng(7)
    for lon_c, lat_c in ((130.9, 33.95), (179.95, -16.7)):
        lon0, lat0 = lon_c + rng.uniform(-0.3, 0.3, 40), lat_c + rng.uniform(-0.2, 0.2, 40)
        lon1, lat1 = lon0 + rng.uniform(-0.3, 0.3, 40), lat0 + rng.uniform(-0.2, 0.2, 40)
        got = LandWalk._exact_hits(lon0, lat0, lon1, lat1)
        want = [np.count_nonzero(final.contains(*densify_track(
            [lon0[s], lon1[s]], [lat0[s], lat1[s]], STEP_M))) for s in range(lon0.size)]
        assert got.tolist() == want
        assert 0 < np.count_nonzero(got) < got.size  # both kinds of segments


def test_search_walk_reads_level1_round_span_ends_beyond_the_latitude_bound():
    # a span from Hammerfest (70.7 N) planned with a latitude bound of 60 degrees: legs near
    # its ends get the same verdicts as with a bound beyond them (level 1 is read there)
    from shiproute_planner.route.land_walk import LandWalk
    from shiproute_planner.route.problem import RouteLimits, RouteProblem

    rng = np.random.default_rng(70)
    lon0, lat0 = 23.7 + rng.uniform(-0.3, 0.3, 80), 70.72 + rng.uniform(-0.1, 0.1, 80)
    lon1 = lon0 + rng.uniform(-0.1, 0.1, 80)
    lat1 = lat0 + rng.uniform(-0.05, 0.05, 80)

    def verdicts(bound_deg: float) -> np.ndarray:
        limits = RouteLimits(rpm_min=40.0, rpm_max=80.0, lat_bound_deg=bound_deg)
        problem = RouteProblem(23.7, 70.72, 19.0, 69.7, 0.0, 86400.0, limits)
        return LandWalk(problem).segments(lon0, lat0, lon1, lat1) > 0

    wide = verdicts(80.0)
    assert 0 < np.count_nonzero(wide) < wide.size
    assert np.array_equal(verdicts(60.0), wide)


def test_search_walk_across_land_asks_no_tile_and_gives_the_same_count_with_or_without_them(
        walk_inputs, tmp_path):
    # legs from the sea across a coast onto land level 0 calls inland (the first level-1
    # read is where level 0 cannot decide, at the coast): a search's stray candidate builds
    # no tile for them, and its count is the same in a process holding every tile
    from shiproute_planner.geo.fine_distance import FineDistance
    from shiproute_planner.route import _land_walk as lw

    final, _, coarse, clear, coarse_deg, room = walk_inputs
    # Pacific -> Nunavut, Gulf of Alaska -> Yukon, Bay of Biscay -> central France
    lon0, lat0 = np.array([-128.0, -146.0, -3.0]), np.array([50.0, 59.0, 46.0])
    lon1, lat1 = np.array([-100.0, -137.0, 2.0]), np.array([62.0, 62.5, 46.5])
    assert final.contains(lon1, lat1).all()  # the legs end on land
    ends = np.array([*lw.unit_vector(0.0, 0.0), *lw.unit_vector(0.5, 0.0)])
    rule = ClearanceRule(1.0, 0.5, 10.0).kernel_array(search=True)

    def walk(tiles: FineDistance) -> tuple[np.ndarray, int]:
        got, missing = np.empty(3, dtype=np.int64), np.empty(256, dtype=np.int64)
        n = lw.clearance_walk(lon0, lat0, lon1, lat1, coarse, clear, coarse_deg,
                              np.asarray(final.mask.coast_distance), final.mask.cell_deg,
                              0.05, tiles.slots, tiles.grids, ends, rule, room, missing, got,
                              np.zeros(3, dtype=np.int64))
        return got, n

    empty = FineDistance(final.tiles.land_near, final.contains, tmp_path / "none.npz")
    got_empty, asked = walk(empty)
    assert asked == 0 and np.all(got_empty > 0)
    # every tile the legs' coast crossings lie in, built: the same counts
    for k in range(3):
        f = np.linspace(0.0, 1.0, 400)
        empty.distance_nm(lon0[k] + f * (lon1[k] - lon0[k]), lat0[k] + f * (lat1[k] - lat0[k]))
    got_full, asked = walk(empty)
    assert asked == 0 and np.array_equal(got_full, got_empty)


def test_search_walk_counts_a_leg_across_an_island_at_least_by_its_samples_on_land(walk_inputs):
    # Tyrrhenian Sea -> across Sicily -> Strait of Sicily: a search's count must not be below
    # the leg's samples on full-resolution land (its sampling: chord fractions k / steps),
    # or a candidate across the island would rank ahead of one merely too close to a coast
    from shiproute_planner.geo.land_kernels import FINE, segment_ends
    from shiproute_planner.route import _land_walk as lw

    final, fine, coarse, clear, coarse_deg, room = walk_inputs
    lon0, lat0 = np.array([13.6]), np.array([38.4])
    lon1, lat1 = np.array([14.2]), np.array([36.8])
    spacing_deg = 0.05
    ax, ay, az, bx, by, bz, arc = segment_ends(lat0[0], lon0[0], lat1[0], lon1[0])
    steps = FINE * max(1, int(np.ceil(arc / spacing_deg)))
    f = np.arange(steps + 1) / steps
    p = np.stack([ax + f * (bx - ax), ay + f * (by - ay), az + f * (bz - az)])
    p /= np.linalg.norm(p, axis=0)
    on_land = final.contains(np.degrees(np.arctan2(p[1], p[0])), np.degrees(np.arcsin(p[2])))
    assert 0 < on_land.sum() < steps  # the leg starts and ends at sea and crosses land
    ends = np.array([*lw.unit_vector(0.0, 0.0), *lw.unit_vector(0.5, 0.0)])
    rule = ClearanceRule(1.0, 0.5, 10.0).kernel_array(search=True)
    got = np.full(1, -1, dtype=np.int64)
    for _ in range(50):  # build the tiles the walk asks for, then walk again
        missing = np.empty(256, dtype=np.int64)
        n = lw.clearance_walk(lon0, lat0, lon1, lat1, coarse, clear, coarse_deg,
                              np.asarray(final.mask.coast_distance), final.mask.cell_deg,
                              spacing_deg, fine.slots, fine.grids, ends, rule, room, missing,
                              got, np.zeros(1, dtype=np.int64))
        if got[0] >= 0:
            break
        fine.add(missing[:n])
    assert got[0] >= on_land.sum()
