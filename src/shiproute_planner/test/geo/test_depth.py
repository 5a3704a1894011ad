"""Depth and under-keel clearance: bathymetry reading, Barrass squat against its published
numbers, and a plan on real ETOPO 2022 data that keeps its UKC round Skerki Bank."""

from __future__ import annotations

from datetime import timedelta
from pathlib import Path

import numpy as np
import pyproj
import pytest
import xarray as xr
from shiproute_core.geodesy import densify_track
from shiproute_core.units import M_S_PER_KNOT
from shiproute_planner.depth_setup import PORT_CLEARANCE_M
from shiproute_planner.errors import BathymetryError
from shiproute_planner.geo.bathymetry import load_depth_grid
from shiproute_planner.geo.depth import Bathymetry, load_bathymetry
from shiproute_planner.planning import plan_voyage
from shiproute_planner.route.under_keel import UnderKeel, barrass_squat_m
from shiproute_planner.ship import load_ship

SKERKI = Path(__file__).parents[1] / "data" / "skerki_etopo2022_30s.nc"
# a great circle along Skerki Bank's long axis (shoals of 11-14 m at ~37.8 N 10.9 E)
A, B = "37.5,10.42", "38.3,11.65"


def _file_depth_along(lon: np.ndarray, lat: np.ndarray) -> np.ndarray:
    """Independent reference: the grid file's depth at points every ~0.05 NM (xarray,
    nearest cell), positive down."""
    ds = xr.open_dataset(SKERKI)
    z = ds["z"].sel(latitude=xr.DataArray(lat), longitude=xr.DataArray(lon), method="nearest")
    return -np.asarray(z.values, dtype=float)


def test_barrass_squat_matches_published_numbers():
    # Barrass's open-water rule Cb V^2 / 100: Cb 0.9 -> 0.144, 0.576, 1.296, 2.304, 3.600 m
    # at 4, 8, 12, 16, 20 kn; confined channel twice that
    v = np.array([4.0, 8.0, 12.0, 16.0, 20.0]) * M_S_PER_KNOT
    assert barrass_squat_m(0.9, v) == pytest.approx([0.144, 0.576, 1.296, 2.304, 3.6], abs=1e-3)
    assert barrass_squat_m(0.9, v, confined=True) == pytest.approx(
        2 * np.array([0.144, 0.576, 1.296, 2.304, 3.6]), abs=1e-3)


def test_required_depth_and_ukc_loss_grow_with_speed():
    bathy = load_bathymetry([SKERKI], with_default=False)
    uk = UnderKeel(bathy, draft_m=12.0, block_coefficient=0.8, margin_m=1.0)
    speeds = np.array([6.0, 10.0, 14.0, 18.0]) * M_S_PER_KNOT
    n = speeds.size
    leg = [np.full(n, x) for x in (10.42, 37.5, 11.65, 38.3)]
    depth, ukc = uk.leg_clearance(*leg, speeds, np.zeros(n), exact=True)
    assert np.all(depth == depth[0])  # the same leg: the same shallowest depth
    # UKC left = depth - draft - Cb V^2 / 100 - margin: 0.8 * (14^2 - 10^2) / 100 = 0.768 m
    assert np.all(np.diff(ukc) < 0)
    assert ukc[1] - ukc[2] == pytest.approx(0.8 * (14**2 - 10**2) / 100.0, abs=1e-9)
    # waves: half the significant wave height more
    _, ukc_waves = uk.leg_clearance(*leg, speeds, np.full(n, 3.0), exact=True)
    assert ukc - ukc_waves == pytest.approx(np.full(n, 1.5))


def test_reads_etopo_2022_grid_positive_up():
    grid = load_depth_grid(str(SKERKI))
    bathy = Bathymetry([grid])
    lon, lat = np.array([10.0021, 11.5021]), np.array([38.2021, 37.6021])  # off cell edges
    ref = _file_depth_along(lon, lat)
    assert bathy.depth_m(lon, lat) == pytest.approx(ref)
    assert np.all(ref > 100)  # open sea: positive depths (the file stores negative heights)
    assert grid.resolution_text == "30 arc-second" and not grid.is_coarse


def test_plan_goes_round_skerki_bank_and_keeps_ukc(land_mask):
    kw = dict(approach_nm=0, land=land_mask, budget_s=60.0, max_generations=40,
              stage_hours=2.0, default_bathymetry=False)
    ship = "container_4600teu"
    blind = plan_voyage(A, B, "2026-06-01T00:00Z", timedelta(hours=12), ship, **kw)
    lon, lat = densify_track(*blind.track()[:2], 90.0)
    # premise: the plan made without depth runs over the bank, shallower than the draft
    assert any(w.startswith("depth not checked") for w in blind.warnings)
    assert _file_depth_along(lon, lat).min() < 12.0

    plan = plan_voyage(A, B, "2026-06-01T00:00Z", timedelta(hours=12), ship,
                       bathymetry=[SKERKI], **kw)
    assert plan.feasible, plan.infeasible_reasons
    assert any("30 arc-second" in w for w in plan.warnings)
    spec = load_ship(ship)
    c, h = spec.condition, spec.hull
    cb = c.displacement_t / 1.025 / (h.lwl_m * h.breadth_m * spec.mean_draft_m)
    draft = max(c.draft_fore_m, c.draft_aft_m)
    p_lon, p_lat, _ = plan.track()
    geod = pyproj.Geod(ellps="WGS84")
    for k, w in enumerate(plan.waypoints[:-1]):
        seg_lon, seg_lat = (np.asarray(v) for v in densify_track(p_lon[k:k + 2],
                                                                   p_lat[k:k + 2], 90.0))
        # the plan leaves the first and last 3 km to the harbour (depth next to a berth)
        for end in (0, -1):
            _, _, off_m = geod.inv(np.full(seg_lon.size, p_lon[end]),
                                   np.full(seg_lon.size, p_lat[end]), seg_lon, seg_lat)
            keep = off_m >= PORT_CLEARANCE_M
            seg_lon, seg_lat = seg_lon[keep], seg_lat[keep]
        depth = _file_depth_along(seg_lon, seg_lat).min()
        # independent UKC: draft + Barrass Cb V^2/100 + margin 1 m (calm: no wave allowance)
        need = draft + cb * w.stw_kn**2 / 100.0 + 1.0
        assert depth >= need - 0.05, (k, depth, need)
        assert w.ukc_m >= 0.0 and w.min_depth_m == pytest.approx(depth, abs=1.0)


def test_bad_bathymetry_files_give_clear_errors(tmp_path):
    with pytest.raises(BathymetryError, match="does not exist"):
        load_depth_grid(str(tmp_path / "none.nc"))
    text = tmp_path / "notes.nc"
    text.write_text("not a grid")
    with pytest.raises(BathymetryError, match="not a readable NetCDF"):
        load_depth_grid(str(text))
    lat, lon = np.linspace(37, 38, 5), np.linspace(10, 11, 6)
    wind = xr.Dataset({"u10": (("lat", "lon"), np.zeros((5, 6)))},
                      coords={"lat": ("lat", lat, {"units": "degrees_north"}),
                              "lon": ("lon", lon, {"units": "degrees_east"})})
    wind.to_netcdf(tmp_path / "wind.nc")
    with pytest.raises(BathymetryError, match=r"no depth or elevation variable.*u10"):
        load_depth_grid(str(tmp_path / "wind.nc"))
    utm = xr.Dataset({"elevation": (("y", "x"), -np.ones((5, 6)))},
                     coords={"y": ("y", np.arange(5) * 1e3, {"units": "m"}),
                             "x": ("x", np.arange(6) * 1e3, {"units": "m"})})
    utm.to_netcdf(tmp_path / "utm.nc")
    with pytest.raises(BathymetryError, match="projected CRS"):
        load_depth_grid(str(tmp_path / "utm.nc"))


def test_node_parameters_for_depth_and_zones_are_validated(tmp_path):
    from shiproute_planner.voyage_params import check_parameter

    assert check_parameter("ukc_margin_m", 1.5) is None
    assert "ukc_margin_m = -1.0 is outside 0..10 m" in check_parameter("ukc_margin_m", -1.0)
    assert "clearance_nm" in check_parameter("clearance_nm", float("nan"))
    assert check_parameter("bathymetry_files", f"{SKERKI}, ") is None
    assert "no such file" in check_parameter("zones_files", str(tmp_path / "none.geojson"))


def test_ship_too_deep_for_the_passage_goes_round(land_mask):
    # the 12 m container ship threads Skerki Bank's 14-20 m gaps; a VLCC (20 m draft) may not
    kw = dict(approach_nm=0, land=land_mask, budget_s=60.0, max_generations=40,
              stage_hours=2.0, default_bathymetry=False, bathymetry=[SKERKI])
    small = plan_voyage(A, B, "2026-06-01T00:00Z", timedelta(hours=14), "container_4600teu",
                        **kw)
    deep = plan_voyage(A, B, "2026-06-01T00:00Z", timedelta(hours=14), "vlcc_270k", **kw)
    spec = load_ship("vlcc_270k")
    c, h = spec.condition, spec.hull
    cb = c.displacement_t / 1.025 / (h.lwl_m * h.breadth_m * spec.mean_draft_m)
    draft = max(c.draft_fore_m, c.draft_aft_m)

    def shallowest(plan):
        lon, lat = densify_track(*plan.track()[:2], 90.0)
        return _file_depth_along(lon, lat).min()

    assert small.feasible and deep.feasible, (small.infeasible_reasons, deep.infeasible_reasons)
    assert shallowest(small) < draft  # the small ship's track would ground the VLCC
    p_lon, p_lat, _ = deep.track()
    for k, w in enumerate(deep.waypoints[:-1]):
        seg_lon, seg_lat = densify_track(p_lon[k:k + 2], p_lat[k:k + 2], 90.0)
        need = draft + cb * w.stw_kn**2 / 100.0 + 1.0
        assert _file_depth_along(seg_lon, seg_lat).min() >= need - 0.05, k
