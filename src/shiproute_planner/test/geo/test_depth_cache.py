"""Prepared coarse depth grids are memory-mapped from the data directory: the same depths as
the grid prepared in memory, to the bit, with no private copy and no pages left resident."""

from __future__ import annotations

import mmap
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from shiproute_planner.geo import bathymetry, depth_cache
from shiproute_planner.geo.depth import Bathymetry

pytestmark = pytest.mark.skipif(not bathymetry.ETOPO5_PATH.is_file(),
                                reason="ETOPO5 (Debian ferret-datasets) not installed")


@pytest.fixture
def etopo5_crop(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """Real ETOPO5 over Korea, Japan and the Sea of Japan (a coarse grid with shelf, coast and
    trench) as a NetCDF file of its own; the data directory in tmp_path."""
    monkeypatch.setenv("SHIPROUTE_DATA_DIR", str(tmp_path / "data"))
    with xr.open_dataset(bathymetry.ETOPO5_PATH, decode_times=False) as ds:
        crop = ds.sel(ETOPO05_Y=slice(28.0, 46.0), ETOPO05_X=slice(122.0, 146.0)).load()
    path = tmp_path / "etopo5_japan.nc"
    crop.to_netcdf(path)
    bathymetry.load_depth_grid.cache_clear()
    yield path
    bathymetry.load_depth_grid.cache_clear()


def _mapped_rss_kb(path: Path) -> int:
    """Resident kB of this process's mappings of `path` (Linux /proc/self/smaps)."""
    total, inside = 0, False
    for line in Path("/proc/self/smaps").read_text().splitlines():
        head = line.split()
        if head and "-" in head[0] and len(head) >= 5 and ":" in head[3]:
            inside = line.endswith(str(path))
        elif inside and line.startswith("Rss:"):
            total += int(head[1])
    return total


def _probe(bathy: Bathymetry, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """Depths at 20,000 random points and the shallowest depth of 2,000 random legs."""
    lon, lat = rng.uniform(121.0, 147.0, 20_000), rng.uniform(27.0, 47.0, 20_000)
    a = rng.uniform([122.0, 28.0], [146.0, 46.0], (2_000, 2))
    b = a + rng.uniform(-1.5, 1.5, (2_000, 2))
    legs = bathy.segment_min_depth_m(a[:, 0], a[:, 1], b[:, 0], b[:, 1])
    return bathy.depth_m(lon, lat), legs


def test_mapped_grid_answers_exactly_as_the_grid_prepared_in_memory(etopo5_crop: Path) -> None:
    prepared = bathymetry.load_depth_grid(str(etopo5_crop))  # read, filtered, stored
    assert prepared.is_coarse and prepared.depth_m.flags.writeable  # ordinary memory
    fresh_points, fresh_legs = _probe(Bathymetry([prepared]), np.random.default_rng(16))
    # ETOPO5 holds whole metres and its preparation takes medians, so float32 is exact here:
    # there is no rounding to allow for
    known = np.isfinite(prepared.depth_m)
    assert np.array_equal(prepared.depth_m[known], np.round(prepared.depth_m[known]))

    bathymetry.load_depth_grid.cache_clear()
    mapped = bathymetry.load_depth_grid(str(etopo5_crop))
    assert not mapped.depth_m.flags.writeable
    assert isinstance(mapped.depth_m.base.base.obj, mmap.mmap)  # the file, not a copy
    for field in ("name", "lat0_deg", "dlat_deg", "lon0_deg", "dlon_deg", "periodic"):
        assert getattr(mapped, field) == getattr(prepared, field)
    assert np.array_equal(mapped.depth_m, prepared.depth_m, equal_nan=True)
    points, legs = _probe(Bathymetry([mapped]), np.random.default_rng(16))
    assert np.array_equal(points, fresh_points, equal_nan=True)
    assert np.array_equal(legs, fresh_legs, equal_nan=True)
    # a sanity anchor independent of the code: the Japan Trench off Honshu is deeper than
    # 6,000 m in every bathymetry, the East China Sea shelf west of Kyushu shallower than
    # 200 m (the Korea Strait itself lies within the coastal cells: no depth, geo.coarse_coast)
    assert Bathymetry([mapped]).depth_m(np.array([144.0]), np.array([38.0]))[0] > 6000.0
    assert Bathymetry([mapped]).depth_m(np.array([127.0]), np.array([31.5]))[0] < 200.0
    assert np.isnan(Bathymetry([mapped]).depth_m(np.array([129.0]), np.array([34.5]))[0])


def test_pre_check_scan_leaves_no_pages_of_the_mapped_grid_resident(etopo5_crop: Path) -> None:
    bathymetry.load_depth_grid(str(etopo5_crop))
    bathymetry.load_depth_grid.cache_clear()
    grid = bathymetry.load_depth_grid(str(etopo5_crop))
    npy, _ = depth_cache.cache_paths(Path(etopo5_crop).parent / "data",
                                     bathymetry.prepared_key(etopo5_crop))
    assert float(grid.depth_m.sum(where=np.isfinite(grid.depth_m))) > 0  # every page read
    assert _mapped_rss_kb(npy) > 0.5 * grid.depth_m.nbytes / 1024
    Bathymetry([grid])  # the pre-check raster reads the whole grid, then lets it go
    assert _mapped_rss_kb(npy) == 0


def test_damaged_prepared_grid_is_prepared_again(etopo5_crop: Path) -> None:
    first = bathymetry.load_depth_grid(str(etopo5_crop))
    npy, desc = depth_cache.cache_paths(Path(etopo5_crop).parent / "data",
                                        bathymetry.prepared_key(etopo5_crop))
    npy.write_bytes(npy.read_bytes()[:1000])  # truncated
    bathymetry.load_depth_grid.cache_clear()
    again = bathymetry.load_depth_grid(str(etopo5_crop))
    assert again.depth_m.flags.writeable  # read and prepared from the NetCDF file again
    assert np.array_equal(again.depth_m, first.depth_m, equal_nan=True)
    assert desc.is_file() and npy.stat().st_size > 1000  # and stored again
