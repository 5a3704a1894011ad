"""Build the comparison's `BaselineInputs` exactly as `planning.plan_voyage` builds a leg.

Ports resolve through the planner's gazetteer and snapping, the ship through
`planning.make_environment` (the tabulated model), limits through the planner's own rule, so a
comparison row and `shiproute plan --method <name>` judge routes identically.
"""

from __future__ import annotations

from datetime import timedelta
from typing import Any

import numpy as np

from ..baselines.inputs import BaselineInputs
from ..geo.landmask import LandMask, default_land_mask
from ..geo.ports import Port, resolve_port
from ..planning import TimeLike, make_environment, route_limits, to_posix_s
from ..route.voyage_legs import leg_setup

DEFAULT_DEPARTURE_AFTER_REFERENCE_H = 6.0  # the reference case sails 6 h after the 12Z run


def load_forecast(name_or_path: str):
    """A bundled scenario by name, else a forecast file through the weather loaders."""
    from shiproute_weather.scenarios.catalogue import scenario_dataset, scenario_names

    if name_or_path in scenario_names():
        return scenario_dataset(name_or_path)
    from shiproute_weather.ingest.loaders import open_forecast

    return open_forecast([name_or_path])


def default_departure_s(ds) -> float:
    """Forecast reference time + 6 h (the reference study's 18:00 departure after a 12Z run)."""
    ref = ds.attrs.get("forecast_reference_time")
    if ref:
        return to_posix_s(str(ref)) + DEFAULT_DEPARTURE_AFTER_REFERENCE_H * 3600.0
    t0 = np.datetime64(ds["time"].values[0], "s").astype(np.int64)
    return float(t0) + DEFAULT_DEPARTURE_AFTER_REFERENCE_H * 3600.0


def build_inputs(
    origin: str | Port,
    destination: str | Port,
    depart: TimeLike,
    rta: TimeLike | timedelta,
    ship: Any,
    forecast: Any = None,
    *,
    stage_hours: float = 12.0,
    land: LandMask | None = None,
    limits: dict | None = None,
) -> BaselineInputs:
    """One-leg voyage as the planner sets it up: the problem between the approaches' sea
    ends (`route.voyage_legs.leg_setup`; the approaches are common to every method), no seed pool:
    every method starts cold."""
    land = land or default_land_mask()
    env, spec = make_environment(ship, forecast)
    lim = route_limits(spec, limits)
    a = origin if isinstance(origin, Port) else resolve_port(origin, land)
    b = destination if isinstance(destination, Port) else resolve_port(destination, land)
    depart_s = to_posix_s(depart)
    rta_s = depart_s + rta.total_seconds() if isinstance(rta, timedelta) else to_posix_s(rta)
    leg = leg_setup(a, b, env, lim, land, depart_s, rta_s, stage_hours=stage_hours)
    return BaselineInputs(leg.problem, env, land)
