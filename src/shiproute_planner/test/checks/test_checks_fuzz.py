"""Property-based fuzzing of the input validators (issue 16): 1,000 generated inputs each.

Every validator either accepts its input - and then what it accepted is usable (a slice packs
into a sampler that samples finite-or-NaN values, a fix is finite and in range, a parameter in
its range, a voyage has resolved ports at sea and a ship) - or raises the package's own error.
Any other exception fails the test.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st
from shiproute_planner.checks.forecast_wire import (
    MAX_CYCLE_STORAGE_BYTES,
    check_slice_fields,
)
from shiproute_planner.checks.parameters import RANGES, check_number, require_number
from shiproute_planner.checks.ship_state import OPTIONAL_RANGES, check_ship_state
from shiproute_planner.errors import ForecastCycleError, ParameterError, PlannerError
from shiproute_planner.ros.cycle_packer import CyclePacker, SliceFields
from shiproute_planner.ship.errors import ShipModelError
from shiproute_weather.contract.canonical import VARIABLES, Grid
from shiproute_weather.wire.packing import PackedField

FUZZ = settings(max_examples=1000, deadline=None, suppress_health_check=[
    HealthCheck.too_slow, HealthCheck.data_too_large])

odd_floats = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([0.0, -0.0, 1e-300, -1.0, 0.5, 5.0, 360.0, 1e308, math.nan, math.inf]))
times = st.sampled_from(range(10)).flatmap(lambda k: st.floats(1.7e9, 1.8e9) if k > 1 else (
    st.floats(allow_nan=True, allow_infinity=True) if k else st.sampled_from([0.0, -1.0])))
canonical = st.sampled_from(sorted(VARIABLES))
names = st.sampled_from(["eastward_wind", "northward_wind",
                         "sea_surface_wave_significant_height",
                         "sea_surface_wave_from_direction", "eastward_sea_water_velocity",
                         "air_temperature", ""])


def maybe(good: st.SearchStrategy, wild: st.SearchStrategy) -> st.SearchStrategy:
    """Mostly plausible values, one time in twelve anything (a slice has ~12 such parts)."""
    return st.sampled_from(range(12)).flatmap(lambda k: wild if k == 0 else good)


@st.composite
def field_values(draw, name: str, n: int):
    """float32 data (with NaN/inf/huge values) or 16-bit codes with any scaling."""
    size = draw(maybe(st.just(n), st.integers(0, 400)))
    spec = VARIABLES.get(name)
    lo, hi = (spec.valid_min, spec.valid_max) if spec else (-20.0, 20.0)
    element = st.one_of(st.floats(lo, hi, width=32), st.just(math.nan),
                        st.floats(width=32, allow_nan=True, allow_infinity=True))
    if draw(st.booleans()):
        return np.array(draw(st.lists(element, min_size=size, max_size=size)), dtype=np.float32)
    codes = draw(st.lists(st.integers(0, 65535), min_size=size, max_size=size))
    return PackedField(np.array(codes, dtype=np.uint16), draw(maybe(st.just(lo), odd_floats)),
                       draw(maybe(st.floats(0, (hi - lo) / 65534), odd_floats)))


@st.composite
def slices(draw):
    """Slices near a valid one (a Pacific grid of a few nodes), each part sometimes wild."""
    n_lat = draw(maybe(st.integers(2, 12), st.integers(0, 2**32 - 1)))
    n_lon = draw(maybe(st.integers(2, 12), st.integers(0, 2**32 - 1)))
    grid = Grid(draw(maybe(st.floats(-60, 30), odd_floats)),
                draw(maybe(st.floats(0.05, 5), odd_floats)), n_lat,
                draw(maybe(st.floats(-180, 300), odd_floats)),
                draw(maybe(st.floats(0.05, 10), odd_floats)), n_lon)
    cells = n_lat * n_lon if n_lat * n_lon <= 144 else 16
    chosen = draw(st.lists(maybe(canonical, names), min_size=draw(maybe(st.just(1),
                                                                       st.just(0))),
                           max_size=3, unique=True))
    fields = tuple((name, draw(field_values(name, cells))) for name in chosen)
    count = draw(maybe(st.integers(1, 3), st.integers(0, 2**32 - 1)))
    index = draw(maybe(st.integers(0, max(count - 1, 0)), st.integers(0, 2**32 - 1)))
    return SliceFields("fuzz", index, count, draw(times), grid, fields,
                       reference_time_s=draw(times))


@FUZZ
@given(s=slices())
def test_forecast_slice_validator(s: SliceFields) -> None:
    try:
        check_slice_fields(s)
    except ForecastCycleError:
        event("refused")
        return
    event("accepted")
    g = s.grid
    assert g.n_lat >= 2 and g.n_lon >= 2
    assert math.isfinite(g.dlat_deg) and g.dlat_deg > 0 and math.isfinite(g.dlon_deg)
    assert g.dlon_deg > 0
    assert all(v.size == g.n_lat * g.n_lon for _, v in s.fields)
    assert s.count * g.n_lat * g.n_lon * 2 <= MAX_CYCLE_STORAGE_BYTES
    # what passed packs and samples: finite-or-NaN values, no exception of another kind
    s1 = SliceFields(s.cycle_id, 0, 1, s.valid_time_s, g, s.fields,
                     reference_time_s=s.reference_time_s)
    if not any(name in VARIABLES for name, _ in s.fields):
        return
    try:
        packer = CyclePacker(s1)
        packer.add(0, s1)
        sampler = packer.result()
    except ForecastCycleError:
        return  # e.g. differing field sets: the package's own error
    event("packed and sampled")
    lat = g.lat0_deg + g.dlat_deg * np.array([0.0, 0.5 * (g.n_lat - 1)])
    lon = g.lon0_deg + g.dlon_deg * np.array([0.0, 0.5 * (g.n_lon - 1)])
    out = sampler.sample(lon, lat, np.full(2, s.valid_time_s))
    for values in out.values():
        assert not np.isinf(values).any()


optional = st.dictionaries(st.sampled_from([n for n, *_ in OPTIONAL_RANGES]),
                           st.one_of(st.floats(0, 30), odd_floats))


@FUZZ
@given(lat=st.one_of(st.floats(-90, 90), odd_floats), lon=st.one_of(st.floats(-180, 180),
                                                                     odd_floats),
       t=times, extra=optional,
       clock=st.one_of(st.none(), times))
def test_ship_state_validator(lat: float, lon: float, t: float, extra: dict, clock) -> None:
    try:
        fix = check_ship_state(lat, lon, t, extra, clock_s=clock)
    except PlannerError:
        event("refused")
        return
    event("accepted")
    assert -90 <= fix.lat_deg <= 90 and -180 <= fix.lon_deg <= 180
    assert math.isfinite(fix.time_s)
    for name, lo, hi, _ in OPTIONAL_RANGES:
        v = extra.get(name, math.nan)
        assert math.isnan(v) or lo <= v <= hi


@FUZZ
@given(name=st.sampled_from(sorted(RANGES)),
       value=st.one_of(odd_floats, st.integers(-2**70, 2**70), st.text(max_size=5),
                       st.booleans(), st.none()))
def test_parameter_validator(name: str, value: object) -> None:
    reason = check_number(name, value)
    try:
        got = require_number(name, value)
    except ParameterError as err:
        assert reason is not None and name in str(err)
        return
    assert reason is None
    rule = RANGES[name]
    assert rule.lowest <= got <= rule.highest


ports = st.one_of(
    st.sampled_from(["Busan", "Long Beach", "Atlantis", "USLGB", "", "Rotterdam", "Kansas"]),
    st.sampled_from(["Long Beach", "Singapore", "Yokohama", "Shanghai", "Halifax"]),
    st.builds(lambda a, b: f"{a},{b}", odd_floats, odd_floats),
    st.text(max_size=12))
ships = st.sampled_from(["container_4600teu", "vlcc_270k", "bulk_supramax", "container_348m",
                         "flying_dutchman", "", "/nonexistent/ship.yaml"])


@FUZZ
@given(dest=ports, lat=st.one_of(st.floats(-60, 60), odd_floats),
       lon=st.one_of(st.floats(-180, 180), odd_floats), rta=times,
       depart=st.one_of(st.none(), times),
       ship=ships, objective=st.sampled_from(["fuel", "eta", "speed", ""]))
def test_voyage_validator(land_mask, dest: str, lat: float, lon: float, rta: float,
                          depart, ship: str, objective: str) -> None:
    from shiproute_planner.voyage_request import VoyageChange, check_voyage_request

    req = VoyageChange(dest, lat, lon, rta, ship, objective)
    try:
        checked = check_voyage_request(
            req, origin="Busan", ship="container_4600teu", objective="fuel", method="seed_ga",
            rta="2026-06-16T18:00:00Z", position=None,
            departure_time="" if depart is None or not math.isfinite(depart) or depart <= 0
            else _iso(depart), clock_s=0.0)
    except (PlannerError, ShipModelError):
        event("refused")
        return
    event("accepted")
    c = checked.check
    assert not land_mask.is_land(np.array([c.destination.lon_deg]),
                                 np.array([c.destination.lat_deg]))[0]
    assert c.depart_s is None or c.rta_s > c.depart_s
    assert c.max_speed_kn > 10.0  # every bundled ship makes more than 10 kn at full RPM
    assert (c.rta_warning == "") == (c.depart_s is None or c.rta_reachable)


def _iso(t: float) -> str:
    from datetime import UTC, datetime

    try:
        return datetime.fromtimestamp(t, UTC).isoformat()
    except (OverflowError, OSError, ValueError):
        return "not a time"

