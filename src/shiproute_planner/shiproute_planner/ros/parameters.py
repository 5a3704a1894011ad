"""The planner node's parameters (default and description) and the kinds of input it counts
when it refuses them; the checks of each value live in `voyage_params.check_parameter`."""

from __future__ import annotations

from ..route.clearance import DEFAULT_CLEARANCE

PARAMETERS: dict[str, tuple[object, str]] = {
    "origin": ("Busan", "departure port (name, UN/LOCODE or 'lat,lon'); seed-pool key"),
    "destination": ("Long Beach", "arrival port (name, UN/LOCODE or 'lat,lon')"),
    "departure_time": ("", "ISO 8601 UTC departure when no ShipState has arrived"),
    "rta": ("2026-03-16T18:00:00Z", "required time of arrival, ISO 8601 UTC"),
    "ship": ("container_4600teu", "bundled ship name or ship file path"),
    "ship_model": ("", "physics | kwon | profile:FILE.nc | learned:FILE.nc; '' = the ship "
                   "file's performance_model, else physics"),
    "objective": ("fuel", "fuel | distance | eta | co2 | cost (a PlanRoute goal may ask for "
                  "the time-fuel front)"),
    "loading": ("", "loading condition: a condition of the ship file (design, ballast) or "
                "drafts 'T_F,T_A' [m]; '' = the file's default"),
    "fuel_type": ("", "fuel burned for the co2/cost objectives (HFO, LFO, MDO, MGO, LNG); "
                  "'' = the ship file's, else HFO"),
    "fuel_price_usd_per_t": (-1.0, "fuel price for the cost objective [USD/t]; < 0 = the "
                             "ship file's economics, else the stated default"),
    "charter_usd_per_day": (-1.0, "time-charter rate for the cost objective [USD/day]; < 0 "
                            "= the ship file's economics, else the stated default"),
    "method": ("seed_ga", "route-finding method"),
    "stage_hours": (0.0, "stage duration [h]; 0 = from the voyage (12 h for an ocean "
                    "crossing, ~12 stages for a short passage)"),
    "rta_tolerance_s": (300.0, "an arrival this much after the RTA or a port's latest arrival "
                        "is on time [s]"),
    "port_calls": ("", "intermediate port calls, ';'-separated "
                   "PORT[@EARLIEST..LATEST][+BERTH_H] (ISO UTC times); set by SetVoyage"),
    "risk": ("", "plan an ensemble on every member minimising mean | cvar:ALPHA (e.g. "
             "cvar:0.9) | worst of the objective; '' = on the members' mean forecast"),
    "p_hs_max": (0.0, "with risk: largest accepted probability (member weight) of meeting Hs "
                 "above the ship's limit along the route (0..1)"),
    "p_late_max": (0.0, "with risk: largest accepted probability of arriving late (0..1)"),
    "budget_s": (3.0, "wall-time budget of one plan [s]"),
    "rng_seed": (0, "seed of the GA's random generator"),
    "seed_pool_dir": ("", "seed pool directory (persists across restarts); '' = none"),
    "output_dir": ("", "directory for each plan's RTZ, GeoJSON, PNG and JSON; '' = none"),
    "write_png": (True, "also draw the PNG of each plan"),
    "replan_cross_track_nm": (20.0, "re-plan when the ship is this far off the track [NM]"),
    "replan_schedule_h": (3.0, "re-plan when this far ahead of/behind schedule [h]"),
    "min_replan_interval_s": (3600.0, "least ship-time between off-plan re-plans [s]"),
    "departure_radius_nm": (10.0, "within this of the origin the plan starts at the port [NM]"),
    "plan_without_ship_state": (False, "plan from origin/departure_time without a ShipState"),
    "bathymetry_files": ("", "bathymetry grids, comma-separated NetCDF paths (finest wins)"),
    "default_bathymetry": (True, "add the global ETOPO5 grid (Debian ferret-datasets)"),
    "ukc_margin_m": (1.0, "under-keel clearance margin on draft + squat + waves [m]"),
    "zones_files": ("", "no-go / avoid zone GeoJSON files, comma-separated"),
    "clearance_nm": (0.0, "distance from land the route check of each plan requires [NM]"),
    "open_sea_clearance_nm": (DEFAULT_CLEARANCE.open_sea_nm,
                              "distance from land the search keeps in open sea [NM]"),
    "approach_clearance_nm": (DEFAULT_CLEARANCE.approach_nm, "distance from land the search "
                              "keeps near the span ends and in narrow water [NM]"),
    "approach_zone_nm": (DEFAULT_CLEARANCE.approach_zone_nm, "radius round the span ends "
                         "(ports, strait exits, the ship) where the approach clearance "
                         "applies [NM]"),
    "approach_files": ("", "coastal passages from/to ports (RTZ/GeoJSON), comma-separated"),
    "accept_older_forecasts": (False, "let a cycle of an older model run replace the one in "
                               "force (e.g. to go back after a bad run)"),
    "ship_state_max_age_h": (366 * 24.0, "drop ship states older than this behind the clock [h]"),
    "ship_state_max_lead_h": (1.0, "drop ship states further ahead of the clock than this [h]"),
}
DROP_KINDS = ("ship_states", "forecast_slices", "forecast_cycles", "voyage_requests",
              "plan_requests")


def goal_objective_reason(objective: str, points: int) -> str | None:
    """Why a PlanRoute goal's objective / front size is refused, or None."""
    from ..objectives import PLAN_OBJECTIVES

    if objective and objective not in PLAN_OBJECTIVES:
        return f"objective {objective!r}: use '' or one of {', '.join(PLAN_OBJECTIVES)}"
    if objective == "front" and not 2 <= points <= 25:
        return f"front_points {points}: use 2..25 (0 = 9)"
    return None


def paths(text: str) -> list[str]:
    """Comma-separated file list of a string parameter."""
    return [p.strip() for p in text.split(",") if p.strip()]


def method_reason(name: str) -> str | None:
    """Why `name` is not a route-finding method (None when it is)."""
    from ..errors import UnknownMethodError
    from ..methods import get_method

    try:
        get_method(name)
    except UnknownMethodError as err:
        return str(err)
    return None
