"""What a plan minimises: fuel, distance, ETA (earliest arrival), CO2 or cost, and the prices
and emission factors behind CO2 and cost.

CO2 = fuel x Cf, the fuel's carbon conversion factor [t CO2 / t fuel] of IMO resolution
MEPC.308(73) (2018 EEDI calculation guidelines, para 2.2; the same values stand in
MEPC.364(79) and are the ones MARPOL Annex VI's DCS/CII reporting uses): HFO 3.114,
LFO 3.151, MDO/MGO 3.206, LNG 2.750. The fuel type comes from the ship file (``fuel_type``,
default HFO). Cost = fuel price x fuel + time-charter rate x time from departure to arrival,
with the prices from the CLI/node, else the ship file's ``economics`` section, else the
defaults below (stated in the plan when used).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from .errors import InvalidVoyageError
from .ship.fuel import CO2_FACTOR_T_PER_T

#: objectives a route search minimises (each is one number per route)
OBJECTIVES = ("fuel", "distance", "eta", "co2", "cost")
#: what `plan --objective` and the node accept: the route objectives or the time-fuel front
PLAN_OBJECTIVES = (*OBJECTIVES, "front")
DEFAULT_FUEL_TYPE = "HFO"
#: stated defaults: a very-low-sulphur fuel oil price and a mid-size container ship's
#: time-charter rate of the mid-2020s, both round figures to be replaced by the user's own
DEFAULT_FUEL_PRICE_USD_PER_T = 600.0
DEFAULT_CHARTER_USD_PER_DAY = 25_000.0
UNITS = {"fuel": "t", "distance": "NM", "eta": "h", "co2": "t CO2", "cost": "USD"}


@dataclass(frozen=True)
class Economics:
    """Fuel type and prices for the CO2 and cost objectives (None: ship file, else default)."""

    fuel_type: str | None = None
    fuel_price_usd_per_t: float | None = None
    charter_usd_per_day: float | None = None

    def __post_init__(self) -> None:
        if self.fuel_type is not None and self.fuel_type.upper() not in CO2_FACTOR_T_PER_T:
            raise InvalidVoyageError(
                f"fuel type {self.fuel_type!r}: use one of {', '.join(CO2_FACTOR_T_PER_T)}")
        for name in ("fuel_price_usd_per_t", "charter_usd_per_day"):
            v = getattr(self, name)
            if v is not None and not (isinstance(v, int | float) and 0.0 <= v < 1e7):
                raise InvalidVoyageError(f"{name} must be a number in 0..1e7, got {v!r}")


@dataclass(frozen=True)
class ObjectiveTerms:
    """An objective as a linear cost: `per_t_fuel` x fuel [t] + `per_h` x time [h] (CO2 and
    cost; fuel is 1 x fuel), with the figures and where they came from for the plan."""

    name: str
    per_t_fuel: float = 1.0
    per_h: float = 0.0
    notes: tuple[str, ...] = ()
    figures: tuple[tuple[str, Any], ...] = ()

    def value(self, fuel_t: float, hours: float) -> float:
        """The objective of a plan with this fuel and time under way."""
        return self.per_t_fuel * fuel_t + self.per_h * hours


def _pick(given: float | str | None, from_file: float | str | None, default: float | str,
          what: str, notes: list[str]) -> Any:
    """The user's value, else the ship file's, else the default (noted)."""
    if given is not None:
        return given
    if from_file is not None:
        return from_file
    notes.append(f"{what} not given (CLI/node or ship file): default {default}")
    return default


def objective_terms(objective: str, ship_economics: dict[str, Any] | None,
                    economics: Economics | None = None) -> ObjectiveTerms:
    """Terms of ``objective`` for a ship whose file gives ``ship_economics`` (keys fuel_type,
    fuel_price_usd_per_t, charter_usd_per_day, any missing), overridden by ``economics``."""
    if objective not in OBJECTIVES:
        raise InvalidVoyageError(f"objective {objective!r}: use one of {', '.join(OBJECTIVES)}")
    if objective not in ("co2", "cost"):
        return ObjectiveTerms(objective)
    eco = economics or Economics()
    fil = ship_economics or {}
    notes: list[str] = []
    fuel_type = str(_pick(eco.fuel_type, fil.get("fuel_type"), DEFAULT_FUEL_TYPE, "fuel type",
                          notes)).upper()
    cf = CO2_FACTOR_T_PER_T[fuel_type]
    if objective == "co2":
        return ObjectiveTerms("co2", cf, 0.0, tuple(notes), (
            ("fuel_type", fuel_type), ("co2_factor_t_per_t", cf),
            ("co2_factor_source", "IMO MEPC.308(73) para 2.2")))
    price = float(_pick(eco.fuel_price_usd_per_t, fil.get("fuel_price_usd_per_t"),
                        DEFAULT_FUEL_PRICE_USD_PER_T, "fuel price [USD/t]", notes))
    rate = float(_pick(eco.charter_usd_per_day, fil.get("charter_usd_per_day"),
                       DEFAULT_CHARTER_USD_PER_DAY, "time-charter rate [USD/day]", notes))
    return ObjectiveTerms("cost", price, rate / 24.0, tuple(notes), (
        ("fuel_type", fuel_type), ("co2_factor_t_per_t", cf),
        ("fuel_price_usd_per_t", price), ("charter_usd_per_day", rate)))


def objective_block(terms: ObjectiveTerms, fuel_t: float, hours: float,
                    distance_nm: float) -> dict[str, Any]:
    """The plan's ``extra["objective"]``: name, value with its unit and the figures used."""
    value = {"distance": distance_nm, "eta": hours}.get(terms.name,
                                                        terms.value(fuel_t, hours))
    out: dict[str, Any] = {"name": terms.name, "value": float(value),
                           "unit": UNITS[terms.name], **dict(terms.figures)}
    if "co2_factor_t_per_t" in out:
        out["co2_t"] = float(fuel_t * out["co2_factor_t_per_t"])
    if terms.name == "cost":
        out["fuel_cost_usd"] = float(terms.per_t_fuel * fuel_t)
        out["time_cost_usd"] = float(terms.per_h * hours)
    return out
