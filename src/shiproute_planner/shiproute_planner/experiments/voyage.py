"""Build the comparison's `BaselineInputs` from a `VoyageRequest` exactly as `planning.plan`
builds a leg.

Ports resolve through the planner's gazetteer and snapping, the ship through
`plan_setup.make_environment` (the tabulated model), limits through the planner's own rule, so a
comparison row and `shiproute plan --method <name>` judge routes identically.
"""

from __future__ import annotations

import numpy as np

from ..baselines.inputs import BaselineInputs
from ..geo.landmask import default_land_mask
from ..geo.ports import Port, resolve_port
from ..plan_setup import make_environment, route_limits, to_posix_s
from ..request import ForecastInput, PlanOptions, VoyageRequest
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


def build_inputs(request: VoyageRequest, options: PlanOptions | None = None,
                 forecast: ForecastInput = None) -> BaselineInputs:
    """The first leg of `request` as the planner sets it up: the problem between the
    approaches' sea ends (`route.voyage_legs.leg_setup`; the approaches are common to every
    method), at `options.stage_hours` (12 h when None), with `options.land` and
    `options.limits`; no seed pool: every method starts cold."""
    options = options or PlanOptions()
    land = options.land or default_land_mask()
    env, spec = make_environment(request.ship, forecast)
    lim = route_limits(spec, dict(options.limits) if options.limits is not None else None)
    a = request.origin if isinstance(request.origin, Port) else resolve_port(request.origin, land)
    b = (request.destination if isinstance(request.destination, Port)
         else resolve_port(request.destination, land))
    stage_hours = 12.0 if options.stage_hours is None else options.stage_hours
    leg = leg_setup(a, b, env, lim, land, request.depart_s, request.rta_s,
                    stage_hours=stage_hours)
    return BaselineInputs(leg.problem, env, land)
