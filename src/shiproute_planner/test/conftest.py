"""Shared fixtures of the planner tests: land mask, ship environments, scenario samplers."""

from __future__ import annotations

import functools

import pytest


@functools.lru_cache(maxsize=4)
def _sampler(name: str):
    from shiproute_weather.sampling.sampler import ForecastSampler
    from shiproute_weather.scenarios.catalogue import scenario_dataset

    return ForecastSampler(scenario_dataset(name))


@pytest.fixture(scope="session")
def storm_sampler():
    return _sampler("storm_march")


@pytest.fixture(scope="session")
def land_mask():
    from shiproute_planner.geo.landmask import default_land_mask

    return default_land_mask()


@pytest.fixture(scope="session")
def calm_env():
    from shiproute_planner.plan_setup import make_environment

    return make_environment("container_4600teu", None)


@pytest.fixture
def empty_tiles(monkeypatch):
    """The process's full-resolution coastline tiles, empty and in memory for one test (as on
    a fresh machine; nothing saved)."""
    from shiproute_planner.geo import fine_distance
    from shiproute_planner.geo.full_land import final_land

    final = final_land()
    tiles = fine_distance.FineDistance(final.tiles.land_near, final.contains, path=None)
    monkeypatch.setattr(fine_distance, "_DEFAULT", {final.resolution: tiles})
    return tiles
