"""A plan says where its depth near the coast was only checked on a coarse grid: legs within
1.5 coarse cells (7.5 NM for a 5 arc-minute grid) of land where no fine grid covers."""

from __future__ import annotations

import numpy as np
from shiproute_planner.coastal_depth import coarse_coastal_legs
from shiproute_planner.geo.bathymetry import DepthGrid
from shiproute_planner.geo.depth import Bathymetry

LAT0 = 20.0
NM_LON = 1.0 / 60.0 / np.cos(np.radians(LAT0))


def _grid(cell_deg: float, lon0: float, lon1: float, name: str) -> DepthGrid:
    lat = np.arange(LAT0 - 1.0, LAT0 + 1.0, cell_deg)
    lon = np.arange(lon0, lon1, cell_deg)
    depth = np.full((lat.size, lon.size), 50.0, dtype=np.float32)
    return DepthGrid(name, depth, float(lat[0]), cell_deg, float(lon[0]), cell_deg, False)


def _land_west_of_zero(lon, lat):
    """A straight coast along the meridian 0: land to its west."""
    return np.asarray(lon) < 0.0


def _track(off_nm: float) -> tuple[np.ndarray, np.ndarray]:
    """Two legs north along a meridian `off_nm` east of the coast, 30 NM each."""
    lon = np.full(3, off_nm * NM_LON)
    lat = LAT0 - 0.5 + np.array([0.0, 0.5, 1.0])
    return lon, lat


COARSE = _grid(5.0 / 60.0, -1.0, 1.0, "coarse 5'")  # trust distance 1.5 x 5 NM = 7.5 NM


def test_track_near_the_coast_on_a_coarse_grid_only_is_named():
    legs, nm, within = coarse_coastal_legs(*_track(4.0), Bathymetry([COARSE]),
                                           _land_west_of_zero)
    assert within == 7.5
    assert legs == [0, 1]
    assert 59.0 - 2 * 1.7 <= nm <= 60.0  # 60 NM of track less the 3 km berths at the ends


def test_track_beyond_the_trust_distance_is_not_named():
    legs, nm, _ = coarse_coastal_legs(*_track(9.0), Bathymetry([COARSE]), _land_west_of_zero)
    assert legs == [] and nm == 0.0


def test_a_fine_grid_covering_the_coast_decides_instead():
    fine = _grid(1.0 / 120.0, -0.2, 0.3, "fine 30''")
    legs, _, _ = coarse_coastal_legs(*_track(4.0), Bathymetry([COARSE, fine]),
                                     _land_west_of_zero)
    assert legs == []
    # only the part of the coast the fine grid does not cover is named
    lon, lat = _track(4.0)
    partial = _grid(1.0 / 120.0, -0.2, 0.3, "fine 30''")
    partial = DepthGrid(partial.name, partial.depth_m[:125], partial.lat0_deg,
                        partial.dlat_deg, partial.lon0_deg, partial.dlon_deg,
                        False)  # 19.0-20.04 N: the first leg and a little of the second
    legs, _, _ = coarse_coastal_legs(lon, lat, Bathymetry([COARSE, partial]),
                                     _land_west_of_zero)
    assert legs == [1]


def test_fixed_passages_are_left_to_their_authority():
    legs, _, _ = coarse_coastal_legs(*_track(4.0), Bathymetry([COARSE]), _land_west_of_zero,
                                     skip_legs=frozenset({0}))
    assert legs == [1]


def test_raster_prefilter_finds_the_same_coastal_legs_as_probing_every_sample() -> None:
    """The land mask's raster only skips samples with no land within reach: on tracks along
    and off a real coast (Portugal, GSHHG) the legs found equal those of probing every sample."""
    from shiproute_planner.geo.landmask import default_land_mask

    land = default_land_mask()
    lat = np.linspace(37.2, 41.8, 12)
    grid = DepthGrid("coarse 5'", np.full((80, 80), 50.0, dtype=np.float32), 36.0, 5.0 / 60.0,
                     -14.0, 5.0 / 60.0, False)
    for lon0 in (-9.05, -9.2, -9.4, -10.5):  # hugging the coast ... well offshore
        lon = np.full(lat.size, lon0) + 0.05 * np.sin(np.arange(lat.size))
        probed = coarse_coastal_legs(lon, lat, Bathymetry([grid]), land.is_land)
        filtered = coarse_coastal_legs(lon, lat, Bathymetry([grid]), land.is_land, land=land)
        assert filtered == probed
    assert coarse_coastal_legs(np.full(3, -9.3), np.array([38.0, 39.0, 40.0]),
                               Bathymetry([grid]), land.is_land, land=land)[0]
