"""The warm re-plan generalises beyond the planner bench: a second voyage (Yokohama ->
Vancouver, June weather, no strait) whose next forecast cycle puts a storm (the scenarios'
Holland-profile storm model, built here) on the previous plan's route. Re-planned 12 h along
with the route evaluations of the first population alone (what a 0.5-s re-plan buys on a
loaded machine; before the track repairs of `track_repairs` none of three seeds ended
feasible here), the plan is feasible, and an independent leg-by-leg march of the published
track on the new cycle confirms it (Hs below the ship's limit on every leg, on time); where
the previous remainder still holds, the re-plan is no dearer than it."""

from __future__ import annotations

import functools
from datetime import timedelta

import numpy as np
import pytest
import xarray as xr
from shiproute_core.geodesy import unwrap_near
from shiproute_planner.plan_position import position_after
from shiproute_planner.plan_setup import make_environment, route_limits
from shiproute_planner.planning import plan
from shiproute_planner.request import PlanOptions, VoyageRequest, voyage_times
from shiproute_planner.route.problem import RouteProblem
from shiproute_planner.route.sail import sail_tracks

SHIP = "container_4600teu"
REFERENCE = "2026-06-03T12:00:00"  # both cycles' time origin (the scenarios' epoch)
REPLAN_EVALUATIONS = 130  # the first population (~120 seeds and copies) and part of one
# generation: what a 0.5-s re-plan's search bought on the planner bench at load 2-3
STORM_DAYS = 4.5  # the storm is centred on the previous route this long after departure


def _voyage() -> VoyageRequest:
    depart_s, rta_s = voyage_times("2026-06-03T18:00Z", timedelta(days=11))
    return VoyageRequest("Yokohama", "Vancouver", depart_s, rta_s, SHIP)


@functools.lru_cache(maxsize=4)
def _cycle(track: tuple = ()):
    """A forecast cycle of June weather (1 deg, 6-hourly, 16 days) with the storm `track`
    (TrackPoints, hours since REFERENCE), as a sampler."""
    from shiproute_weather.contract import canonical as cv
    from shiproute_weather.sampling.sampler import ForecastSampler
    from shiproute_weather.scenarios.fields import build_fields
    from shiproute_weather.scenarios.synth_seas import JUNE_SWELL
    from shiproute_weather.scenarios.synth_wind import JUNE

    lat = np.arange(20.0, 62.0 + 1e-9, 1.0)
    lon = np.arange(120.0, 240.0 + 1e-9, 1.0)
    hours = np.arange(0.0, 384.0 + 1e-9, 6.0)
    fields = build_fields(JUNE, JUNE_SWELL, list(track), np.random.default_rng(7), lat, lon,
                          hours)
    times = np.datetime64(REFERENCE, "ns") + (hours * 3600.0).astype("timedelta64[s]")
    ds = xr.Dataset({n: (("time", "latitude", "longitude"), a.astype(np.float32))
                     for n, a in fields.items()},
                    coords={"time": times.astype("datetime64[ns]"), "latitude": lat,
                            "longitude": lon},
                    attrs={"forecast_reference_time": REFERENCE + "Z",
                           "source": "test: June weather with a storm on the route",
                           "cycle_id": f"storm-{len(track)}"})
    return ForecastSampler(cv.annotate(ds))


def _storm_on(previous, deficit_hpa: float):
    """A storm moving east-north-east along the previous route, centred on it STORM_DAYS
    after departure (deepest there), as the next cycle's forecast."""
    from shiproute_weather.scenarios.synth_wind import TrackPoint

    lon, lat, t = previous.track()
    k = int(np.searchsorted(t, previous.departure_s + STORM_DAYS * 86400.0))
    h = (t[k] - np.datetime64(REFERENCE, "s").astype(float)) / 3600.0
    return _cycle((TrackPoint(h - 36.0, lat[k] - 1.0, lon[k] - 6.0, 0.6 * deficit_hpa, 300.0,
                              1.2),
                   TrackPoint(h, lat[k], lon[k], deficit_hpa, 300.0, 1.2),
                   TrackPoint(h + 36.0, lat[k] + 1.0, lon[k] + 6.0, 0.8 * deficit_hpa, 320.0,
                              1.2)))


def _marched(lon, lat, rpm, start_s: float, sampler):
    """A track sailed at `rpm` per leg from `start_s` by the leg-by-leg march (one piece,
    no land test: only the weather is in question here)."""
    env, spec = make_environment(SHIP, sampler)
    lon = np.unwrap(np.asarray(lon, dtype=float), period=360.0)
    problem = RouteProblem(lon[0], lat[0], lon[-1], lat[-1], start_s, start_s + 30 * 86400.0,
                           route_limits(spec))
    return sail_tracks(problem, env, None, lon[None, :], np.asarray(lat)[None, :],
                       np.asarray(rpm, dtype=float)[None, :])


def _remainder(previous, position, sampler):
    """The previous plan's nodes after the ship's time, from its position, marched on
    `sampler` at the plan's leg RPMs."""
    lon, lat, t = previous.track()
    first = int(np.flatnonzero(t > position[2])[0])
    r_lon = np.concatenate([[position[1]], unwrap_near(lon[first:], position[1])])
    r_lat = np.concatenate([[position[0]], lat[first:]])
    return _marched(r_lon, r_lat, previous.leg_rpm()[first - 1:], position[2], sampler)


@pytest.fixture(scope="module")
def previous(land_mask):
    """A seed-GA plan on the storm-free cycle, reproducible (route evaluations)."""
    p = plan(_voyage(), PlanOptions(land=land_mask, budget_s=600.0, max_evaluations=800,
                                    seed=3), _cycle())
    assert p.feasible
    return p


def _replan(previous, land_mask, cycle, seed: int):
    return plan(_voyage(), PlanOptions(
        land=land_mask, budget_s=600.0, max_evaluations=REPLAN_EVALUATIONS, seed=seed,
        previous_plan=previous, position=position_after(previous, 12.0),
        with_baseline=False), cycle)


def test_a_storm_moved_onto_the_route_is_re_planned_round_feasibly(previous, land_mask):
    cycle = _storm_on(previous, 60.0)  # ~950 hPa: a deep winter storm
    pos = position_after(previous, 12.0)
    limit_m = route_limits(make_environment(SHIP, None)[1]).max_hs_m
    stale = _remainder(previous, pos, cycle)
    # the new cycle breaks the previous route: its remainder meets seas above the limit
    assert np.nanmax(stale.legs["hs_m"]) > limit_m
    voyage = _voyage()
    for seed in (0, 1, 2):
        out = _replan(previous, land_mask, cycle, seed)
        assert out.feasible, (seed, out.infeasible_reasons)
        assert out.extra["replan"]["kept_previous"] is False
        # independent check of the published plan: its nodes marched leg by leg at its RPMs
        lon, lat, _ = out.track()
        sailed = _marched(lon, lat, out.leg_rpm(), out.departure_s, cycle)
        assert np.nanmax(sailed.legs["hs_m"]) <= limit_m, seed
        assert sailed.eta_s[0] <= voyage.rta_s + voyage.rta_tolerance_s, seed
        assert sailed.fuel_t[0] == pytest.approx(out.total_fuel_t, rel=2e-3)


def test_a_re_plan_where_the_previous_route_holds_is_no_dearer_than_it(previous, land_mask):
    # the next cycle re-issues the weather; 48 h along the previous remainder, marched
    # independently, is on time and within every limit: the re-plan may not cost more
    voyage = _voyage()
    pos = position_after(previous, 48.0)
    stale = _remainder(previous, pos, _cycle())
    assert stale.violation[0] <= 0.0
    assert stale.eta_s[0] <= voyage.rta_s + voyage.rta_tolerance_s
    out = plan(voyage, PlanOptions(
        land=land_mask, budget_s=600.0, max_evaluations=REPLAN_EVALUATIONS, seed=0,
        previous_plan=previous, position=pos, with_baseline=False), _cycle())
    assert out.feasible
    assert out.total_fuel_t <= float(stale.fuel_t[0]) * (1.0 + 1e-4)
    assert out.extra["replan"]["previous_remaining_fuel_t"] == pytest.approx(
        float(stale.fuel_t[0]), rel=1e-4)
