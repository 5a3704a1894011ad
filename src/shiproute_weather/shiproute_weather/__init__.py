"""shiproute_weather: forecast files -> canonical dataset -> sampling, wire slices and the node.

Rooms, each importing only rooms listed before it: `contract` (canonical dataset), `physics`
(wave physics), `wire` (slices, 16-bit packing), `sampling` (sampler, kernels), `ingest`
(files -> canonical dataset -> cycle; time coverage), `scenarios` (synthetic storms), then
`ros` (node, messages) and `experiments` (benches). Only `ros` touches ROS types.

Public entry points (imported lazily so `import shiproute_weather` stays light):
`open_forecast`, `ForecastSampler`, `scenario_dataset`, `scenario_path`, `scenario_names`.
"""

from __future__ import annotations

from typing import Any

# pyproj's PROJ must be loaded before ecCodes (GRIB): the ecCodes wheels carry PROJ symbols of
# their own and whichever loads first wins; pyproj loaded second finds no database ("no
# database context specified") and the process may crash at exit. Importing pyproj here, before
# anything of this package can import eccodes/cfgrib, keeps both working.
import pyproj  # noqa: F401

__all__ = ["ForecastSampler", "open_forecast", "scenario_dataset", "scenario_names",
           "scenario_path"]

_WHERE = {"ForecastSampler": "sampling.sampler", "open_forecast": "ingest.loaders",
          "scenario_dataset": "scenarios.catalogue", "scenario_names": "scenarios.catalogue",
          "scenario_path": "scenarios.catalogue"}


def __getattr__(name: str) -> Any:
    if name in _WHERE:
        import importlib

        return getattr(importlib.import_module(f".{_WHERE[name]}", __name__), name)
    raise AttributeError(f"module 'shiproute_weather' has no attribute {name!r}")
