"""`shiproute check`: a route over the Isles of Scilly is flagged at full resolution, one round
them passes; depth, zones and bad inputs."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from shiproute_planner.cli.check import main as check_main
from shiproute_planner.errors import RouteFileError, ZoneFileError
from shiproute_planner.geo.zones import load_zones
from shiproute_planner.io.route_read import read_route

SKERKI = Path(__file__).parent / "data" / "skerki_etopo2022_30s.nc"
# St Mary's and Tresco lie at 49.91-49.97 N, 6.27-6.37 W; St Agnes' south tip ~49.88 N
OVER = [(49.93, -6.9), (49.93, -5.9)]
ROUND = [(49.93, -6.9), (49.72, -6.40), (49.93, -5.9)]


def _rtz(path: Path, points: list[tuple[float, float]]) -> Path:
    wps = "".join(
        f'<waypoint id="{k + 1}"><position lat="{la}" lon="{lo}"/>'
        + ('<leg speedMax="12"/>' if k else "") + "</waypoint>"
        for k, (la, lo) in enumerate(points))
    path.write_text('<?xml version="1.0"?><route xmlns="http://www.cirm.org/RTZ/1/2" '
                    f'version="1.2"><routeInfo routeName="{path.stem}"/><waypoints>{wps}'
                    "</waypoints></route>")
    return path


def _geojson(path: Path, points: list[tuple[float, float]]) -> Path:
    path.write_text(json.dumps({"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {"sog_kn": 12.0},
         "geometry": {"type": "LineString", "coordinates": [[lo, la] for la, lo in points]}}]}))
    return path


def test_route_over_scilly_is_flagged_round_passes(tmp_path, capsys):
    over, round_ = _rtz(tmp_path / "over.rtz", OVER), _rtz(tmp_path / "round.rtz", ROUND)
    base = ["--no-default-bathymetry", "--resolution", "f"]
    assert check_main([str(over), *base]) == 1
    out = capsys.readouterr().out
    assert "land" in out and "leg   0" in out and "GSHHG full resolution" in out
    assert check_main([str(round_), *base]) == 0
    assert "OK: no violations" in capsys.readouterr().out
    # the same round route as GeoJSON: its nearest GSHHG-full land is the Western Rocks
    # (49.872 N 6.450 W), 6.6 NM from the first leg (pyproj geodesics to every vertex)
    gj = _geojson(tmp_path / "round.geojson", ROUND)
    assert check_main([str(gj), *base, "--clearance-nm", "6.3"]) == 0
    capsys.readouterr()
    assert check_main([str(gj), *base, "--clearance-nm", "6.9"]) == 1
    out = capsys.readouterr().out
    assert "clearance" in out and "leg   0" in out


def test_depth_and_zone_violations_are_listed(tmp_path, capsys):
    # along Skerki Bank's axis: shoals of 11-14 m for a 12 m draft
    bank = _rtz(tmp_path / "bank.rtz", [(37.5, 10.42), (38.3, 11.65)])
    args = [str(bank), "--no-default-bathymetry", "--bathymetry", str(SKERKI),
            "--resolution", "i"]
    assert check_main(args) == 1
    out = capsys.readouterr().out
    assert "depth" in out and "UKC -" in out
    zones = tmp_path / "zones.geojson"
    zones.write_text(json.dumps({"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {"name": "exercise area", "mode": "hard"},
         "geometry": {"type": "Polygon", "coordinates": [[[11.0, 37.7], [11.3, 37.7],
                                                           [11.3, 38.1], [11.0, 38.1],
                                                           [11.0, 37.7]]]}}]}))
    assert check_main([*args[:1], "--no-default-bathymetry", "--resolution", "i",
                       "--zones", str(zones)]) == 1
    assert "no-go zone 'exercise area'" in capsys.readouterr().out


def test_bad_route_and_zone_files(tmp_path, capsys):
    one = _rtz(tmp_path / "one.rtz", [(49.9, -6.9)])
    with pytest.raises(RouteFileError, match="1 waypoint"):
        read_route(one)
    assert check_main([str(one)]) == 2
    assert "at least 2" in capsys.readouterr().err
    bad = tmp_path / "zones.geojson"
    bad.write_text("POLYGON((0 0, 1 0, 1 1, 0 0))")
    with pytest.raises(ZoneFileError, match="is not GeoJSON"):
        load_zones(bad)
    line = tmp_path / "line.geojson"
    line.write_text(json.dumps({"type": "Feature", "properties": {"name": "cable"},
                                "geometry": {"type": "LineString",
                                             "coordinates": [[0, 0], [1, 1]]}}))
    with pytest.raises(ZoneFileError, match="cable is a LineString"):
        load_zones(line)
    route = _rtz(tmp_path / "r.rtz", OVER)
    assert check_main([str(route), "--zones", str(bad), "--resolution", "i"]) == 2
    assert check_main([str(route), "--bathymetry", str(tmp_path / "none.nc")]) == 2


def test_given_approach_is_sailed_as_given_and_checked(land_mask, tmp_path):
    from datetime import timedelta

    from shiproute_planner.planning import plan_voyage

    given = [(49.0, -6.0), (48.8, -6.5), (48.5, -6.6)]  # lat, lon: from the departure
    path = _rtz(tmp_path / "dep.rtz", given)
    plan = plan_voyage("49.0,-6.0", "45.0,-10.0", "2026-06-01T00:00Z", timedelta(days=2),
                       "container_4600teu", land=land_mask, budget_s=30.0,
                       max_generations=5, default_bathymetry=False,
                       approaches_given=[path])
    first = [(round(w.lat_deg, 6), round(w.lon_deg, 6)) for w in plan.waypoints[:3]]
    assert first == given
    assert plan.optimised_spans[0][0] == 2  # the method plans from the given passage's end
    with pytest.raises(RouteFileError, match="1 waypoint"):
        plan_voyage("49.0,-6.0", "45.0,-10.0", "2026-06-01T00:00Z", timedelta(days=2),
                    "container_4600teu", land=land_mask, default_bathymetry=False,
                    approaches_given=[_rtz(tmp_path / "one.rtz", [(49.0, -6.0)])])
