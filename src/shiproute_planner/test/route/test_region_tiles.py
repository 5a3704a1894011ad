"""The tiles a warm-up builds for a voyage's region: the box between the ports the shorter
way round, whichever port comes first."""

from __future__ import annotations

import numpy as np
from shiproute_planner.geo import fine_distance
from shiproute_planner.route.clearance import DEFAULT_CLEARANCE
from shiproute_planner.route.land_walk import build_region_tiles

SUVA, LAMBASA = (178.42, -18.14), (-179.6, -16.4)  # Fiji, across the antimeridian


def test_region_is_the_same_box_either_way_and_the_short_way_round(empty_tiles):
    margins = (0.0, 0.0, 0.0, 0.0)
    built = build_region_tiles(SUVA, LAMBASA, margins, DEFAULT_CLEARANCE)
    keys_east = set(empty_tiles._keys[:empty_tiles.count].tolist())
    assert built == len(keys_east) > 0
    # the other way: nothing new to build (the same box)
    assert build_region_tiles(LAMBASA, SUVA, margins, DEFAULT_CLEARANCE) == 0
    # every tile lies within the box between the ports across the antimeridian (~2 x 4
    # tiles of 0.5 deg: 178.0..180.0 and -180.0..-179.5 east, 18.5..16.0 south)
    rows, cols = np.divmod(np.array(sorted(keys_east)), fine_distance.TILE_COLS)
    lat = -90.0 + rows * fine_distance.TILE_DEG
    lon = -180.0 + cols * fine_distance.TILE_DEG
    assert np.all((lat >= -18.5) & (lat < -16.0))
    assert np.all((lon >= 178.0) | (lon < -179.0))


def test_region_box_runs_the_short_way_round_either_way():
    from shiproute_planner.geo.region_box import region_box

    # 170E -> 170W is 20 deg eastward across the antimeridian (340 deg the other way)
    box = region_box((170.0, 10.0), (-170.0, 20.0), (1.0, 2.0, 3.0, 4.0))
    assert box == (169.0, 192.0, 7.0, 24.0)
    assert region_box((-170.0, 20.0), (170.0, 10.0), (1.0, 2.0, 3.0, 4.0)) == box
    # latitudes capped short of the poles
    assert region_box((0.0, 80.0), (10.0, -80.0), (0.0, 0.0, 10.0, 10.0))[2:] == (-85.0, 85.0)
