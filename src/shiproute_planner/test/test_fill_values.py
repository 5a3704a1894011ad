"""Shelf fill values of coarse bathymetry: found from the file's own histogram."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from shiproute_planner.geo.fill_values import shelf_fill_values

ETOPO5 = Path("/usr/share/ferret-vis/data/etopo5.cdf")


def test_an_over_represented_shelf_value_is_found_and_a_smooth_shelf_has_none():
    rng = np.random.default_rng(3)
    shelf = rng.uniform(0.5, 60.0, 200_000).round()  # ~3,400 cells per metre
    assert shelf_fill_values(shelf).size == 0
    filled = np.concatenate([shelf, np.full(20_000, 10.0)])  # a compilation's "10 m" shelf
    assert shelf_fill_values(filled).tolist() == [10.0]
    bank = np.concatenate([shelf, np.full(3_000, 12.0)])  # a real bank doubling one value
    assert shelf_fill_values(bank).size == 0


@pytest.mark.skipif(not ETOPO5.is_file(), reason="Debian ferret-datasets not installed")
def test_etopo5_fill_values_are_its_1_and_10_metre_shelves():
    import xarray as xr

    rose = xr.open_dataset(ETOPO5)["ROSE"].values  # heights, positive up
    found = shelf_fill_values(-rose.astype(float)).tolist()
    # independent count: 10 m occurs 58,872 times, 9 m 5,771 and 11 m 4,516 (np.bincount)
    assert 1.0 in found and 10.0 in found
    assert not set(found) & {2.0, 5.0, 9.0, 11.0, 12.0, 15.0, 20.0}
