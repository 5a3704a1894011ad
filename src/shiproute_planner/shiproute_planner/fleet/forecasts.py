"""Forecasts held once per process, keyed by content hash: every voyage a worker plans on the
same forecast shares one dataset and one sampler (loading is seconds; planning a voyage at a
fixed evaluation budget is about as long)."""

from __future__ import annotations

import threading
from dataclasses import dataclass
from typing import Any, overload

from .keys import forecast_files

_CACHE: dict[str, LoadedForecast] = {}
_LOCK = threading.Lock()
_LOADS: list[str] = []  # keys loaded by this process, in order (a statistic for tests/bench)
MAX_HELD = 4  # forecasts one process keeps (a day's cycles); the oldest is dropped


@dataclass(frozen=True)
class LoadedForecast:
    """A canonical dataset, its sampler and cycle id."""

    dataset: Any
    sampler: Any
    cycle_id: str


def load_forecast_spec(spec: str) -> LoadedForecast:
    """Load a forecast spec (file, files joined with '+', or bundled scenario)."""
    from shiproute_weather.sampling.sampler import ForecastSampler
    from shiproute_weather.scenarios.catalogue import scenario_dataset, scenario_names

    if spec in scenario_names():
        ds = scenario_dataset(spec)
    else:
        from shiproute_weather.ingest.loaders import open_forecast

        ds = open_forecast([str(p) for p in forecast_files(spec)])
    return LoadedForecast(ds, ForecastSampler(ds), str(ds.attrs.get("cycle_id", "")))


@overload
def cached_forecast(spec: str, key: str) -> LoadedForecast: ...


@overload
def cached_forecast(spec: None, key: str) -> None: ...


@overload
def cached_forecast(spec: str | None, key: str) -> LoadedForecast | None: ...


def cached_forecast(spec: str | None, key: str) -> LoadedForecast | None:
    """The forecast `spec` with content hash `key`, loaded at most once in this process."""
    if spec is None:
        return None
    with _LOCK:
        hit = _CACHE.get(key)
        if hit is None:
            hit = load_forecast_spec(spec)
            _LOADS.append(key)
            if len(_CACHE) >= MAX_HELD:
                _CACHE.pop(next(iter(_CACHE)))
            _CACHE[key] = hit
        return hit


def loads(dask_worker: Any = None) -> list[str]:
    """Keys of every forecast load this process made, in order (for tests and the bench)."""
    with _LOCK:
        return list(_LOADS)
