"""What a plan is set up from: times, the forecast file or scenario, the ship's model and
limits, the RTA check and the cancel hook (shared by `planning`, the CLI, benches and nodes)."""

from __future__ import annotations

import itertools
from collections.abc import Callable, Sequence
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from shiproute_core.geodesy import inverse
from shiproute_core.units import M_PER_NM

from .errors import InvalidVoyageError
from .geo.ports import Port
from .route.environment import Environment
from .route.problem import RouteLimits

TimeLike = datetime | float | int | str


def to_posix_s(value: TimeLike) -> float:
    """UTC datetime, ISO 8601 string ('Z' allowed) or POSIX seconds -> POSIX seconds."""
    if isinstance(value, int | float):
        return float(value)
    if isinstance(value, str):
        value = datetime.fromisoformat(value.strip().replace("Z", "+00:00"))
    if value.tzinfo is None:
        value = value.replace(tzinfo=UTC)
    return value.timestamp()



def load_forecast(name_or_path: str | Sequence[str], waves_from_wind: bool = True) -> Any:
    """Canonical forecast dataset from file paths (one cycle: wind, waves and currents may
    come from different files) or a bundled scenario name. A file that cannot be used is
    refused with InvalidVoyageError naming it and the reason."""
    from shiproute_weather.errors import WeatherError
    from shiproute_weather.scenarios.catalogue import scenario_dataset, scenario_names

    names = [name_or_path] if isinstance(name_or_path, str | Path) else list(name_or_path)
    if len(names) == 1 and not Path(names[0]).exists() and names[0] in scenario_names():
        return scenario_dataset(str(names[0]))
    for n in names:
        if not Path(n).exists():
            raise InvalidVoyageError(
                f"forecast {str(n)!r} is neither a file nor a bundled scenario "
                f"({', '.join(scenario_names())})")
    from shiproute_weather.ingest.loaders import open_forecast

    try:
        return open_forecast([str(n) for n in names], waves_from_wind=waves_from_wind)
    except WeatherError as exc:
        raise InvalidVoyageError(f"forecast refused: {exc}") from exc



def make_environment(ship: Any, forecast: Any = None) -> tuple[Environment, Any]:
    """Environment from a ship (name, path, ShipSpec or model) and forecast (Dataset, sampler
    or None for calm water). Returns (environment, ShipSpec or None)."""
    from .ship import ShipSpec, load_ship

    spec = None
    if isinstance(ship, str | Path):
        spec = load_ship(ship)
    elif isinstance(ship, ShipSpec):
        spec = ship
    model = ship if spec is None else fast_model(spec)
    if spec is None:
        spec = getattr(model, "ship", None) or getattr(model, "spec", None)
    sampler, cycle = None, ""
    if forecast is not None:
        if hasattr(forecast, "sample"):
            sampler = forecast
            cycle = str(getattr(forecast, "cycle_id", "") or "")
        else:
            from shiproute_weather.sampling.sampler import ForecastSampler

            sampler = ForecastSampler(forecast)
            cycle = str(forecast.attrs.get("cycle_id", ""))
    return Environment(model, sampler, cycle), spec



def fast_model(spec: Any) -> Any:
    """The tabulated ship model (cached per ship and loading condition)."""
    from .ship.fast import fast_model

    return fast_model(spec)



def route_limits(spec: Any, overrides: dict | None = None) -> RouteLimits:
    """Route limits of a ship (engine RPM range, seakeeping criteria) with `overrides`."""
    kw: dict[str, Any] = {}
    if spec is not None:
        kw.update(rpm_min=spec.engine.rpm_min, rpm_max=spec.engine.rpm_max,
                  max_hs_m=spec.seakeeping.max_hs_m, max_wind_m_s=spec.seakeeping.max_wind_m_s,
                  p_slamming_max=spec.seakeeping.slamming_probability,
                  p_deck_wetness_max=spec.seakeeping.deck_wetness_probability,
                  p_propeller_emergence_max=spec.seakeeping.propeller_emergence_probability)
    kw.update(overrides or {})
    if "rpm_min" not in kw or "rpm_max" not in kw:
        raise InvalidVoyageError("RPM range unknown: give a ship file or limits rpm_min/rpm_max")
    return RouteLimits(**kw)



def chosen_model(ship: Any, ship_model: str) -> tuple[Any, tuple[str, ...]]:
    """(ship or performance model, notes for the plan's warnings) for a `ship_model` choice."""
    from .ship import ShipSpec, load_ship

    if not isinstance(ship, str | Path | ShipSpec):
        if ship_model:
            raise InvalidVoyageError("give ship_model with a ship name/file, not with a model")
        return ship, ()
    spec = ship if isinstance(ship, ShipSpec) else load_ship(ship)
    if (ship_model or spec.performance_model or "physics") == "physics":
        return spec, ()
    from .learned.select import resolve_model
    from .ship import ShipModelError

    try:
        return resolve_model(spec, ship_model)
    except ShipModelError as exc:  # wrong ship, unreadable model file, unknown choice
        raise InvalidVoyageError(f"ship model: {exc}") from exc



def rta_warning_of(ports: list[Port], depart_s: float, rta_s: float,
                 spec: Any) -> tuple[str, float]:
    """Why the RTA cannot be met even on great circles at full calm-water speed ('' when it
    can, or without a ship file), and the arrival time at that speed [POSIX s]."""
    if spec is None:
        return "", rta_s
    from .checks.voyage import max_calm_speed_kn

    dist_nm = sum(float(inverse(a.lon_deg, a.lat_deg, b.lon_deg, b.lat_deg)[1])
                  for a, b in itertools.pairwise(ports)) / M_PER_NM
    need_kn = dist_nm / ((rta_s - depart_s) / 3600.0)
    top_kn = max_calm_speed_kn(spec)
    earliest_s = depart_s + dist_nm / top_kn * 3600.0
    if need_kn <= top_kn:
        return "", rta_s
    return (f"RTA unreachable: {dist_nm:.0f} NM (great circle, the shortest possible) in "
            f"{(rta_s - depart_s) / 3600:.1f} h needs {need_kn:.1f} kn, the ship makes at most "
            f"{top_kn:.1f} kn in calm water; best-effort plan (earliest arrival)"), earliest_s



def cancel_fn(cancel: Any) -> Callable[[], bool]:
    if cancel is None:
        return lambda: False
    if hasattr(cancel, "is_set"):
        return cancel.is_set
    return cancel
