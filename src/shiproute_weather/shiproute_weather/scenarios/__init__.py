"""Bundled synthetic storm scenarios (North Pacific, deterministic, written as NetCDF).

The one entry point for callers outside this room: a scenario's name -> its canonical dataset
or file. Planning never needs this room except to resolve a scenario name given as forecast.
"""

from __future__ import annotations

from .catalogue import scenario_dataset, scenario_names, scenario_path

__all__ = ["scenario_dataset", "scenario_names", "scenario_path"]
