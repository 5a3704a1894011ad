"""Bundled synthetic storm scenarios (North Pacific, deterministic, written as NetCDF).

One entry point for callers outside this room: `scenarios.catalogue` (`scenario_names`,
`scenario_dataset`, `scenario_path`), a scenario's name -> its canonical dataset or file.
Planning needs this room only to resolve a scenario name given as the forecast.
"""
