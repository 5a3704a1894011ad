"""GSHHG polygons stored once per machine and memory-mapped afterwards must be the very
polygons parsed from the basemap files, and a damaged copy must be parsed again."""

from __future__ import annotations

import numpy as np
import pytest
from shiproute_planner.geo import gshhg
from shiproute_planner.geo.gshhg_cache import FIELDS, cached_polygon_arrays


@pytest.fixture()
def fresh_dir(tmp_path, monkeypatch):
    monkeypatch.setenv("SHIPROUTE_DATA_DIR", str(tmp_path))
    return tmp_path


def test_cached_polygons_equal_the_parsed_ones_and_are_memory_mapped(fresh_dir):
    parsed = gshhg._parse_arrays("c")
    first = cached_polygon_arrays("c", gshhg._parse_arrays)
    again = cached_polygon_arrays("c", lambda _r: pytest.fail("parsed although cached"))
    for f in FIELDS:
        np.testing.assert_array_equal(first[f], parsed[f])
        np.testing.assert_array_equal(again[f], parsed[f])
        assert isinstance(again[f], np.memmap)
    # the crude set still holds the continents: Eurasia's ring is its largest polygon
    assert parsed["count"].max() > 1000 and len(parsed["start"]) == len(parsed["bounds"])


def test_a_damaged_copy_is_parsed_again(fresh_dir):
    cached_polygon_arrays("c", gshhg._parse_arrays)
    victim = next(fresh_dir.glob("gshhg_c_*_bounds.npy"))
    victim.write_bytes(b"not an array")
    calls = []

    def parse(resolution):
        calls.append(resolution)
        return gshhg._parse_arrays(resolution)

    arrays = cached_polygon_arrays("c", parse)
    assert calls == ["c"]
    np.testing.assert_array_equal(arrays["bounds"], gshhg._parse_arrays("c")["bounds"])
