"""Port approaches: coastal passages sailed on the lane, and what is left of one under way."""

from __future__ import annotations

from datetime import timedelta

import numpy as np
from shiproute_core.geodesy import inverse
from shiproute_core.units import M_PER_NM
from shiproute_planner.geo.ports import resolve_port
from shiproute_planner.geo.verify import land_crossings
from shiproute_planner.planning import plan_voyage
from shiproute_planner.route.approach import CoastalPassage, approach_length_m, lane_approaches
from shiproute_planner.route.voyage_legs import previous_arrival

JUNE = "2026-06-10T00:00Z"


def test_coastal_passage_ends_where_the_ends_see_each_other_over_open_sea(land_mask):
    busan, long_beach = (resolve_port(n, land_mask) for n in ("Busan", "Long Beach"))
    dep, arr = lane_approaches(busan, long_beach, 25 * M_PER_NM,
                               coastal=CoastalPassage(land_mask))
    a = (float(dep.lon_deg[-1]), float(dep.lat_deg[-1]))
    b = (float(arr.lon_deg[0]), float(arr.lat_deg[0]))
    # the straight (great-circle) ocean passage between the approaches' ends is land-free on
    # the dense polygon check, and the one between the 25-NM approach ends is not (Japan)
    lon = np.array([a[0], b[0] + 360.0 * (b[0] < a[0])])
    assert land_crossings(lon, np.array([a[1], b[1]]), port_clearance_m=0.0) == []
    short_dep, short_arr = lane_approaches(busan, long_beach, 25 * M_PER_NM)
    s_lon = np.array([short_dep.lon_deg[-1], short_arr.lon_deg[0] + 360.0])
    assert land_crossings(s_lon, np.array([short_dep.lat_deg[-1], short_arr.lat_deg[0]]),
                          port_clearance_m=0.0) != []
    # through the Tsugaru Strait (~140.5 E, 41.5 N) and no farther than a sixth of the lane
    assert dep.lon_deg.max() > 141.0 and 40.5 < dep.lat_deg[-1] < 43.5
    lane_m = float(inverse(busan.lon_deg, busan.lat_deg, long_beach.lon_deg,
                           long_beach.lat_deg)[1])
    assert approach_length_m(dep) < lane_m / 5.0 and approach_length_m(arr) < lane_m / 5.0


def test_replan_under_way_finishes_the_coastal_passage_ahead_of_the_ship(land_mask):
    first = plan_voyage("Busan", "Long Beach", JUNE, timedelta(days=13), "container_4600teu",
                        None, budget_s=60.0, max_generations=3, land=land_mask)
    lon, lat, t = first.track()
    start = first.optimised_spans[0][0]
    k = max(1, start // 2)  # a waypoint inside the departure approach (Sea of Japan)
    now = 0.5 * (t[k] + t[k + 1])
    f = (now - t[k]) / (t[k + 1] - t[k])
    pos = (lat[k] + f * (lat[k + 1] - lat[k]), lon[k] + f * (lon[k + 1] - lon[k]), now)
    again = plan_voyage("Busan", "Long Beach", JUNE, timedelta(days=13), "container_4600teu",
                        None, previous_plan=first, position=pos, budget_s=60.0,
                        max_generations=3, land=land_mask)
    w = again.waypoints
    assert (w[0].lat_deg, w[0].lon_deg) == (pos[0], float(np.mod(pos[1] + 180, 360) - 180))
    # the next waypoint is the previous plan's next one: ahead, not back along the lane
    assert np.isclose(w[1].lat_deg, lat[k + 1]) and np.isclose(w[1].lon_deg % 360,
                                                               lon[k + 1] % 360)
    a = again.optimised_spans[0][0]
    assert np.isclose(w[a].lat_deg, lat[start]) and np.isclose(w[a].lon_deg % 360,
                                                               lon[start] % 360)
    # the arrival approach (coastal passage to Long Beach) is the previous plan's, node for node
    end, again_end = first.optimised_spans[-1][1], again.optimised_spans[-1][1]
    a_lon, a_lat, _ = again.track()
    assert len(w) - again_end == len(first.waypoints) - end
    assert np.allclose(a_lat[again_end:], lat[end:], atol=1e-9)
    assert np.allclose(a_lon[again_end:] % 360, lon[end:] % 360, atol=1e-9)
    # ... but not once the ship is inside it, nor for another destination
    busan, long_beach = (resolve_port(n, land_mask) for n in ("Busan", "Long Beach"))
    inside = (lat[end + 1], lon[end + 1], t[end] + 1.0)
    assert previous_arrival(first, long_beach, pos) is not None
    assert previous_arrival(first, long_beach, inside) is None
    assert previous_arrival(first, busan, pos) is None


def test_resolve_box_resolves_every_coastal_cell_once(land_mask):
    fine = land_mask.fine_coast
    fine.resolve_box(140.0, 141.0, 41.0, 42.0)
    assert fine.resolve_box(140.0, 141.0, 41.0, 42.0) == 0
    raster = np.asarray(land_mask.raster)
    i0, j0 = int((41.0 + 90.0) / 0.05), int((140.0 + 180.0) / 0.05)
    ii, jj = np.nonzero(raster[i0:i0 + 20, j0:j0 + 20] == 2)
    keys = (ii + i0) * raster.shape[1] + jj + j0
    assert keys.size > 50 and np.all(np.isin(keys, fine.keys))


def test_resolve_voyage_spans_the_antimeridian_eastward(land_mask):
    fine = land_mask.fine_coast
    # Near Islands -> Andreanof Islands (Aleutians): 175 E eastward to 175 W, 0.5-deg margins
    fine.resolve_voyage((175.0, 51.0), (-175.0, 52.5), (0.5, 0.5, 0.5, 0.5))
    assert fine.resolve_voyage((175.0, 51.0), (-175.0, 52.5), (0.5, 0.5, 0.5, 0.5)) == 0
    raster = np.asarray(land_mask.raster)
    i0, i1 = int((50.5 + 90.0) / 0.05), int((53.0 + 90.0) / 0.05)
    cols = (np.arange(int(174.5 / 0.05), int(185.5 / 0.05)) + int(180.0 / 0.05)) % raster.shape[1]
    ii, jj = np.nonzero(raster[i0:i1][:, cols] == 2)
    keys = (ii + i0) * raster.shape[1] + cols[jj]
    assert keys.size > 50 and np.all(np.isin(keys, fine.keys))
    # both sides of 180 deg hold coast here (Attu ~173 E.. 187 E = Adak ~176.6 W)
    assert (cols[jj] < raster.shape[1] // 2).any() and (cols[jj] > raster.shape[1] // 2).any()


def test_approaches_from_inner_waters_reach_water_that_sees_the_lane_ahead(land_mask):
    # Anchorage (up Cook Inlet) and Vancouver (behind Vancouver Island): no two approach ends
    # see each other, and ends left at the minimum put the optimised span's seam across the
    # islands. Each end must see the lane 100 NM further on over open water, judged here
    # with shapely on the GSHHG full-resolution polygons
    import shapely
    from pyproj import Geod
    from shiproute_planner.geo.gshhg import load_land_polygons
    from shiproute_planner.geo.sea_lanes import sea_lane_between

    a, b = resolve_port("Anchorage", land_mask), resolve_port("Vancouver", land_mask)
    dep, arr = lane_approaches(a, b, 25 * M_PER_NM, coastal=CoastalPassage(land_mask))
    lane = sea_lane_between(a.lon_deg, a.lat_deg, b.lon_deg, b.lat_deg)
    geod = Geod(ellps="WGS84")
    polygons = load_land_polygons("f")
    for (e_lon, e_lat), lane_ahead in (((dep.lon_deg[-1], dep.lat_deg[-1]), lane),
                                       ((arr.lon_deg[0], arr.lat_deg[0]), lane[::-1])):
        _, _, d = geod.inv(np.full(len(lane_ahead), e_lon), np.full(len(lane_ahead), e_lat),
                           lane_ahead[:, 0], lane_ahead[:, 1])
        k = int(np.argmin(d))  # the lane node at the end, then 100 NM on along the lane
        _, _, seg = geod.inv(lane_ahead[k:-1, 0], lane_ahead[k:-1, 1], lane_ahead[k + 1:, 0],
                             lane_ahead[k + 1:, 1])
        j = k + int(np.searchsorted(np.cumsum(seg), 100 * M_PER_NM))
        pts = geod.npts(e_lon, e_lat, lane_ahead[j, 0], lane_ahead[j, 1], 200)
        line = shapely.LineString([(e_lon, e_lat), *pts, tuple(lane_ahead[j])])
        bb = polygons.bounds
        lo, la = line.bounds[0::2], line.bounds[1::2]
        near = np.flatnonzero((bb[:, 0] <= lo[1]) & (bb[:, 2] >= lo[0]) & (bb[:, 1] <= la[1])
                              & (bb[:, 3] >= la[0]))
        assert not any(shapely.Polygon(polygons.ring(int(i))).intersects(line) for i in near)
