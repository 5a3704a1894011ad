"""What a plan was made with: forecast fields and their files, time coverage, route off the grid.

`prepare_forecast` refuses a forecast that misses the voyage and bounds its persistence in
time (`shiproute_weather.ingest.coverage`); `forecast_statement` states, once the route is known,
the fields used and where they came from, the valid-time range, the hours (and %) of the
voyage the forecast covers, what was used beyond it, and the hours and miles of the route
outside the forecast grid. The statement goes into `RoutePlan.extra["forecast"]` (the JSON
summary's `forecast` block) and its sentences into `RoutePlan.warnings`.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .errors import InvalidVoyageError

#: canonical field groups and what their absence means for the plan
_GROUPS = {
    "wind": ("eastward_wind", "northward_wind"),
    "waves": ("sea_surface_wave_significant_height", "sea_surface_wind_wave_significant_height",
              "sea_surface_swell_wave_significant_height"),
    "currents": ("eastward_sea_water_velocity", "northward_sea_water_velocity"),
}


def prepare_forecast(sampler: Any, depart_s: float, rta_s: float,
                     persistence_h: float, climatology: Any = None) -> Any:
    """The sampler to plan with: refused when its valid times miss the voyage altogether;
    bounded in time (persistence, then the monthly `climatology` dataset if given, else calm)
    when the voyage may run beyond them."""
    if sampler is None or not hasattr(sampler, "times_s"):
        return sampler
    from shiproute_weather.errors import ForecastCoverageError
    from shiproute_weather.ingest.coverage import bounded_in_time, require_overlap

    times = getattr(sampler, "forecast_times_s", sampler.times_s)
    cycle = (getattr(sampler, "record", None) or {}).get("cycle_id", "") or "forecast"
    try:
        require_overlap(times, depart_s, rta_s, cycle)
    except ForecastCoverageError as exc:
        raise InvalidVoyageError(str(exc)) from exc
    # a plan may arrive after its RTA; the bounded sampler copies the field array once, so it
    # is built only when the voyage reaches past the forecast (a late plan beyond this slack
    # meets the clamped edge, and the statement says persistence for those hours)
    slack = 12 * 3600.0
    if times is sampler.times_s and (depart_s < times[0] or rta_s + slack > times[-1]):
        try:
            out = bounded_in_time(sampler, persistence_h, climatology, rta_s + slack)
        except ForecastCoverageError as exc:
            raise InvalidVoyageError(str(exc)) from exc
        if climatology is not None:
            out.climatology = str(climatology.attrs.get("source_files", "climatology"))
        if getattr(sampler, "members", None) is not None:  # each member keeps its own edges
            from shiproute_weather.sampling.members import bounded_members

            out.members = bounded_members(sampler.members, times, out.times_s,
                                          out.kernel_data.view(out.dtype),
                                          max(persistence_h, 0.0) * 3600.0)
        return out
    return sampler


def _outside_grid(sampler: Any, lon: np.ndarray, lat: np.ndarray) -> np.ndarray:
    """Which points lie outside the forecast grid (latitude rows, regional longitudes)."""
    g = sampler.grid
    lat_top = g.lat0_deg + g.dlat_deg * (g.n_lat - 1)
    out = (lat < g.lat0_deg - 1e-9) | (lat > lat_top + 1e-9)
    if not g.is_global_in_lon:
        rel = (lon - g.lon0_deg) % 360.0
        out |= rel > g.dlon_deg * (g.n_lon - 1) + 1e-9
    return out


def forecast_statement(sampler: Any, plan: Any, persistence_h: float
                       ) -> tuple[dict[str, Any], list[str]]:
    """(the JSON `forecast` block, warning sentences) for a plan made with `sampler`."""
    if sampler is None:
        return ({"used": False}, ["no forecast: planned in calm water (no wind, waves or "
                                  "currents)"])
    from shiproute_weather.ingest.coverage import time_coverage

    record = getattr(sampler, "record", None) or {}
    times = np.asarray(getattr(sampler, "forecast_times_s", sampler.times_s))
    clim = str(getattr(sampler, "climatology", "") or "")
    bounded = times is not sampler.times_s
    cov = time_coverage(times, plan.departure_s, plan.eta_s,
                        persistence_h if bounded else float("inf"), clim)
    wps = plan.waypoints
    lon = np.array([w.lon_deg for w in wps])
    lat = np.array([w.lat_deg for w in wps])
    outside = _outside_grid(sampler, lon, lat)
    leg_s = np.array([w.leg_duration_s for w in wps[:-1]], dtype=float)
    leg_nm = np.array([w.leg_distance_nm for w in wps[:-1]], dtype=float)
    # a leg counts as outside when either end is
    off = outside[:-1] | outside[1:] if len(wps) > 1 else np.zeros(0, dtype=bool)
    off_h = float(np.nansum(leg_s[off])) / 3600.0
    off_nm = float(np.nansum(leg_nm[off]))
    fields = record.get("fields") or {n: {"source_file": "", "source_variable": n}
                                      for n in sampler.variables}
    present = set(sampler.variables)
    warnings: list[str] = []
    notes = list(record.get("notes", []))
    if not record.get("notes"):  # no load record (a sampler packed elsewhere): say what lacks
        notes = [f"no {g} in the forecast: {g} taken as zero"
                 for g, names in _GROUPS.items() if not present.intersection(names)]
    warnings.extend(n for n in notes if not n.startswith("converted:"))
    warnings.extend(cov.statements())
    if off_h > 0:
        warnings.append(f"{off_h:.1f} h ({off_nm:.0f} NM) of the route lie outside the forecast "
                        "grid: calm water assumed there")
    block = {
        "used": True, "cycle_id": record.get("cycle_id", plan.cycle_id),
        "source_files": list(record.get("source_files", [])),
        "fields": {n: fields.get(n, {"source_file": ""}) for n in sampler.variables},
        "valid_from": _iso(float(times[0])), "valid_to": _iso(float(times[-1])),
        "voyage_hours": cov.voyage_h, "covered_hours": cov.forecast_h,
        "covered_pct": cov.covered_pct, "persistence_limit_hours": cov.persistence_limit_h,
        "persistence_hours": cov.persistence_h,
        "calm_hours": 0.0 if clim else cov.calm_h,
        "climatology_hours": cov.calm_h if clim else 0.0, "climatology_file": clim or None,
        "outside_grid_hours": off_h, "outside_grid_nm": off_nm,
        "outside_grid_pct": 100.0 * off_h / cov.voyage_h if cov.voyage_h > 0 else 0.0,
        "notes": notes,
    }
    return block, warnings


def _iso(t_s: float) -> str:
    from datetime import UTC, datetime

    return datetime.fromtimestamp(t_s, UTC).strftime("%Y-%m-%dT%H:%M:%SZ")
