"""ROS-free parts of the bridge display: geometry, schedule, thinning, feed, coastline, server.

References are independent of the code under test: the spherical midpoint formula, haversine
distances, a brute-force block maximum, known land and sea positions, raw HTTP requests.
"""

from __future__ import annotations

import itertools
import json
import math
import socket
import subprocess
import sys
import time

import numpy as np
import pytest
from geojson_check import check_geojson
from shiproute_display.coastline import ChartBox, coastline_rings
from shiproute_display.errors import MalformedMessageError
from shiproute_display.feed import RESYNC, Feed
from shiproute_display.forecast_view import HS_MISSING, GridSpec, thin_slice
from shiproute_display.model import Plan, Stage, Waypoint, check_plan
from shiproute_display.server import DisplayServer, Routes

from shiproute_display import geometry

R_NM = 3440.065  # mean Earth radius [NM]


def _haversine_nm(lat1: float, lon1: float, lat2: float, lon2: float) -> float:
    p1, p2, dl = math.radians(lat1), math.radians(lat2), math.radians(lon2 - lon1)
    h = math.sin((p2 - p1) / 2) ** 2 + math.cos(p1) * math.cos(p2) * math.sin(dl / 2) ** 2
    return 2 * R_NM * math.asin(math.sqrt(h))


def _midpoint(lat1: float, lon1: float, lat2: float, lon2: float) -> tuple[float, float]:
    """Spherical midpoint (aviation formulary)."""
    p1, p2, l1 = math.radians(lat1), math.radians(lat2), math.radians(lon1)
    dl = math.radians(lon2 - lon1)
    bx, by = math.cos(p2) * math.cos(dl), math.cos(p2) * math.sin(dl)
    pm = math.atan2(math.sin(p1) + math.sin(p2), math.hypot(math.cos(p1) + bx, by))
    lm = l1 + math.atan2(by, math.cos(p1) + bx)
    return math.degrees(pm), (math.degrees(lm) + 180) % 360 - 180


def _plan(points: list[tuple[float, float, float]], rpms: list[float]) -> Plan:
    wps = tuple(Waypoint(lat, lon, t, 90.0, rpm, 15.0, 15.0, 100.0, 3600.0, 1.0, 2.0, 5.0, 0)
                for (lat, lon, t), rpm in zip(points, [*rpms, math.nan], strict=True))
    return Plan("p1", "c1", "seed_ga", "fuel", "ship", "", 0.0, points[0][2], points[-1][2],
                points[-1][2], True, (), (), 100.0, 1000.0, 110.0, 1.0, wps)


def test_library_does_not_import_rclpy():
    code = ("import sys; import shiproute_display.state, shiproute_display.server, "
            "shiproute_display.coastline, shiproute_display.samples; "
            "print('rclpy' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


@pytest.mark.parametrize("a,b", [((35.1, 129.0), (33.7, -118.2)), ((-33.9, 18.4), (-31.9, 115.8)),
                                 ((51.0, 1.5), (40.7, -74.0)), ((0.0, 179.0), (0.0, -179.0))])
def test_slerp_follows_the_great_circle(a, b):
    mid = geometry.slerp(*a, *b, 0.5)
    ref = _midpoint(*a, *b)
    assert mid[0] == pytest.approx(ref[0], abs=1e-9)
    assert geometry.wrap_lon(mid[1] - ref[1]) == pytest.approx(0.0, abs=1e-9)
    total = _haversine_nm(*a, *b)
    for f in (0.1, 0.37, 0.9):
        p = geometry.slerp(*a, *b, f)
        assert _haversine_nm(*a, *p) == pytest.approx(f * total, rel=1e-9, abs=1e-6)


def test_antimeridian_split_keeps_longitudes_in_range():
    pts = geometry.great_circle(40.0, 170.0, 40.0, -170.0, 9)
    pieces = geometry.split_antimeridian(pts)
    assert len(pieces) == 2
    assert pieces[0][-1][1] == 180.0 and pieces[1][0][1] == -180.0
    assert pieces[0][-1][0] == pytest.approx(pieces[1][0][0])
    # the crossing latitude lies on the great circle: its vertex (max latitude) is at 180
    vertex_lat = max(p[0] for p in pts)
    assert pieces[0][-1][0] == pytest.approx(vertex_lat, abs=0.05)
    for piece in pieces:
        assert all(-180.0 <= lon <= 180.0 for _, lon in piece)
        assert all(abs(b[1] - a[1]) < 180 for a, b in itertools.pairwise(piece))


def test_position_at_and_schedule():
    t0 = 1.7e9
    plan = _plan([(30.0, 140.0, t0), (30.0, 150.0, t0 + 10 * 3600), (35.0, 160.0, t0 + 20 * 3600)],
                 [70.0, 75.0])
    assert geometry.position_at(plan, t0 - 100) == (30.0, 140.0, 0)
    lat, lon, leg = geometry.position_at(plan, t0 + 5 * 3600)
    ref = _midpoint(30.0, 140.0, 30.0, 150.0)
    assert leg == 0 and lat == pytest.approx(ref[0], abs=1e-9) and lon == pytest.approx(ref[1])
    assert geometry.position_at(plan, t0 + 99 * 3600)[:2] == (35.0, 160.0)
    stages = [Stage(t0, 3600, 70.0, 90), Stage(t0 + 3600, 3600, 70.2, 90),
              Stage(t0 + 7200, 3600, 75.0, 90), Stage(t0 + 10800, 3600, 75.0, 90)]
    assert geometry.stage_index(stages, t0 - 1) == -1
    assert geometry.stage_index(stages, t0 + 3700) == 1
    # a 0.2 rpm step is not an engine order; the next change is to 75 rpm at stage 3
    assert geometry.next_rpm_change(stages, t0 + 10) == (t0 + 7200, 75.0)
    assert geometry.next_rpm_change(stages, t0 + 8000) is None


@pytest.mark.parametrize("lon,zone", [(135.0, 9), (-118.2, -8), (2.0, 0), (179.0, 12),
                                      (-178.0, -12), (-75.0, -5), (181.0, -12)])
def test_nautical_zone(lon, zone):
    assert geometry.zone_offset_h(lon) == zone


def test_malformed_plans_are_named():
    t0 = 1.7e9
    with pytest.raises(MalformedMessageError, match="1 waypoint"):
        check_plan(_plan([(30.0, 140.0, t0)], []))
    with pytest.raises(MalformedMessageError, match="waypoint 1: position"):
        check_plan(_plan([(30.0, 140.0, t0), (math.nan, 150.0, t0 + 1)], [70.0]))
    with pytest.raises(MalformedMessageError, match="backwards"):
        check_plan(_plan([(30.0, 140.0, t0), (31.0, 150.0, t0 - 1)], [70.0]))


def test_thinning_keeps_the_block_maximum():
    rng = np.random.default_rng(3)
    n_lat, n_lon = 53, 131
    hs = rng.uniform(0, 12, size=(n_lat, n_lon)).astype(np.float32)
    hs[:5, :7] = np.nan  # land
    u = rng.normal(0, 10, size=n_lat * n_lon).astype(np.float32)
    v = rng.normal(0, 10, size=n_lat * n_lon).astype(np.float32)
    grid = GridSpec(10.0, 0.5, n_lat, 115.0, 0.5, n_lon)
    view = thin_slice(7, 1.7e9, grid, {"sea_surface_wave_significant_height": hs.ravel(),
                                       "eastward_wind": u, "northward_wind": v}, max_cells=2000)
    g = view.hs_grid
    stride = round(g.dlat_deg / 0.5)
    assert g.n_lat * g.n_lon <= 2000 and stride == math.ceil(math.sqrt(n_lat * n_lon / 2000))
    codes = np.frombuffer(view.hs_codes, dtype=np.uint8).reshape(g.n_lat, g.n_lon)
    for i in range(g.n_lat):
        for j in range(g.n_lon):
            block = hs[i * stride:(i + 1) * stride, j * stride:(j + 1) * stride]
            if np.isnan(block).all():
                assert codes[i, j] == HS_MISSING
            else:
                assert abs(codes[i, j] * 0.1 - np.nanmax(block)) <= 0.05 + 1e-6
    # cell centres: the first thinned cell covers source rows/columns 0..stride-1
    assert g.lat0_deg == pytest.approx(10.0 + (stride - 1) * 0.25)
    w = np.asarray(view.wind).reshape(-1, 4)
    assert w.shape[0] == math.ceil(n_lat / 5) * math.ceil(n_lon / 5)  # every 2.5 deg
    with pytest.raises(MalformedMessageError, match="expected 53 x 131"):
        thin_slice(0, 0.0, grid, {"eastward_wind": u[:-1]})


def test_feed_never_blocks_and_bounds_a_stalled_client():
    feed = Feed(max_clients=2, depth=4)
    stalled = feed.subscribe()
    t0 = time.perf_counter()
    for k in range(10_000):
        feed.publish("ship", {"k": k, "x": [1.0] * 50})
    assert time.perf_counter() - t0 < 2.0
    assert stalled.queued() <= 4 and stalled.dropped >= 10_000 - 4
    assert stalled.next(0.01) is RESYNC  # the writer sends a fresh snapshot, not stale events
    feed.publish("plan", {"plan_id": "new"})
    assert b'"plan_id":"new"' in stalled.next(0.01)
    feed.subscribe()
    with pytest.raises(Exception, match="2 live pages"):
        feed.subscribe()
    frame = feed.publish("x", {"v": math.nan})
    assert b'"v":null' in frame  # standard JSON


def _contains(ring: np.ndarray, lon: float, lat: float) -> bool:
    """Even-odd point in polygon."""
    x, y = ring[:, 0], ring[:, 1]
    inside = False
    for i in range(len(ring) - 1):
        if (y[i] > lat) != (y[i + 1] > lat):
            xc = x[i] + (lat - y[i]) * (x[i + 1] - x[i]) / (y[i + 1] - y[i])
            if lon < xc:
                inside = not inside
    return inside


def test_coastline_puts_land_and_sea_where_they_are():
    rings = coastline_rings(ChartBox(120.0, 250.0, 20.0, 62.0), 0.05)
    land = [(138.73, 35.36), (360 - 118.25, 34.05), (360 - 150.0, 61.2)]  # Fuji, LA, Anchorage
    sea = [(150.0, 35.0), (180.0, 40.0), (360 - 140.0, 30.0), (135.0, 34.0 - 1.5)]
    for lon, lat in land:
        assert any(_contains(r, lon, lat) for r in rings), (lon, lat)
    for lon, lat in sea:
        assert not any(_contains(r, lon, lat) for r in rings), (lon, lat)


def test_sample_plan_geojson_is_valid_and_split_at_180():
    from shiproute_display.geojson import chart_geojson
    from shiproute_display.model import ShipFix
    from shiproute_display.samples import load_sample_plan

    rp = load_sample_plan("plan_cycle1")
    plan = Plan(rp.plan_id, rp.cycle_id, rp.method, rp.objective, rp.ship_name, "", 0.0,
                rp.departure_s, rp.rta_s, rp.eta_s, rp.feasible, (), rp.warnings,
                rp.total_fuel_t, rp.total_distance_nm, rp.baseline_fuel_t, 1.0,
                tuple(Waypoint(w.lat_deg, w.lon_deg, w.time_s, w.heading_deg, w.shaft_rpm,
                               w.sog_kn, w.stw_kn, w.leg_distance_nm, w.leg_duration_s,
                               w.leg_fuel_t, w.hs_m, w.wind_speed_m_s, w.constraint_flags)
                      for w in rp.waypoints))
    fix = ShipFix(rp.departure_s, 35.0, 129.5, 15.0, 90.0, 90.0, 70.0, 2.0, 1)
    gj = json.loads(json.dumps(chart_geojson(plan, None, plan, [(35.0, 129.5), (35.2, 130.0)],
                                             fix), allow_nan=False))
    names = check_geojson(gj)
    line = next(f for f in gj["features"] if f["properties"]["name"].startswith("plan "))
    assert len(line["geometry"]["coordinates"]) == 2  # Busan -> Long Beach crosses 180
    n_nodes = sum(len(p) for p in line["geometry"]["coordinates"])
    assert n_nodes == len(plan.waypoints) + 2  # + the two points on the antimeridian
    assert "own ship" in names and "great circle (reference)" in names


@pytest.fixture()
def server():
    routes = Routes(snapshot=lambda: {"plan": None, "stats": {}},
                    coast=lambda: b'{"rings":[]}',
                    forecast_slice=lambda cycle, i, member: (
                        b"{}" if (cycle, i, member) == ("c", 1, "0") else None),
                    geojson=lambda: {"type": "FeatureCollection", "features": []},
                    health=lambda: {"ok": True})
    srv = DisplayServer(routes, Feed(max_clients=1, depth=4), "127.0.0.1", 0,
                        client_timeout_s=2.0, heartbeat_s=0.2)
    srv.start()
    yield srv
    srv.stop()


def _get(port: int, raw: str) -> tuple[int, bytes]:
    with socket.create_connection(("127.0.0.1", port), timeout=5) as s:
        s.sendall(raw.encode())
        data = b""
        while b"\r\n\r\n" not in data or (b"event-stream" in data and b"snapshot" not in data):
            chunk = s.recv(65536)
            if not chunk:
                break
            data += chunk
        if b"event-stream" not in data:
            while chunk := s.recv(65536):
                data += chunk
    return int(data.split(b" ", 2)[1]), data


@pytest.mark.parametrize("path,code", [
    ("/", 200), ("/index.html", 200), ("/chart.js", 200), ("/licenses.txt", 200),
    ("/api/coast", 200), ("/api/forecast?cycle=c&index=1", 200),
    ("/api/forecast?cycle=c&index=2", 404), ("/api/forecast", 400),
    ("/../README.md", 400), ("/web/..%2F..%2Fserver.py", 400), ("/%2E%2E/etc/passwd", 400),
    ("/web/", 404), ("/web/app.js", 404), ("/server.py", 404), ("/secret", 404)])
def test_server_routes(server, path, code):
    status, data = _get(server.address[1], f"GET {path} HTTP/1.1\r\nHost: h\r\n"
                                           "Connection: close\r\n\r\n")
    assert status == code
    if code == 200:
        assert b"Content-Security-Policy: default-src 'self'" in data


def test_server_methods_and_live_feed(server):
    port = server.address[1]
    assert _get(port, "DELETE / HTTP/1.1\r\nHost: h\r\nConnection: close\r\n\r\n")[0] == 405
    status, data = _get(port, "GET /events HTTP/1.1\r\nHost: h\r\n\r\n")
    assert status == 200 and b"text/event-stream" in data and b"event: snapshot" in data
    # a second page beyond max_clients=1 is refused while the first is connected
    with socket.create_connection(("127.0.0.1", port), timeout=5) as first:
        first.sendall(b"GET /events HTTP/1.1\r\nHost: h\r\n\r\n")
        first.recv(4096)
        assert _get(port, "GET /events HTTP/1.1\r\nHost: h\r\nConnection: close\r\n\r\n")[0] == 503


def test_server_binds_localhost_by_default():
    srv = DisplayServer(Routes(dict, bytes, lambda c, i: None, dict, dict), Feed(), port=0)
    try:
        assert srv.address[0] == "127.0.0.1"
    finally:
        srv.stop()
    with pytest.raises(Exception, match="not an IP address"):
        DisplayServer(Routes(dict, bytes, lambda c, i: None, dict, dict), Feed(),
                      host="localhost; rm", port=0)
