"""The ship file's fuel and economics entries: fuel type (for its CO2 factor), fuel price and
time-charter rate (for the cost objective), all optional.

``fuel_type``: one of CO2_FACTOR_T_PER_T, whose values are the carbon conversion factors Cf
[t CO2 / t fuel] of IMO resolution MEPC.308(73), para 2.2 (kept in MEPC.364(79)).
``economics``: ``fuel_price_usd_per_t``, ``charter_usd_per_day``.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from .errors import ShipFileError

CO2_FACTOR_T_PER_T = {"HFO": 3.114, "LFO": 3.151, "MDO": 3.206, "MGO": 3.206, "LNG": 2.750}
ECONOMICS_KEYS = ("fuel_price_usd_per_t", "charter_usd_per_day")


def parse_economics(root: Mapping[str, Any], source: str) -> tuple[tuple[str, Any], ...]:
    """(key, value) pairs of the file's fuel_type and economics entries (hashable)."""
    out: list[tuple[str, Any]] = []
    if root.get("fuel_type") is not None:
        fuel = str(root["fuel_type"]).strip().upper()
        if fuel not in CO2_FACTOR_T_PER_T:
            known = ", ".join(CO2_FACTOR_T_PER_T)
            raise ShipFileError(source, "fuel_type", f"'{root['fuel_type']}': use one of {known}")
        out.append(("fuel_type", fuel))
    eco = root.get("economics")
    if eco is None:
        return tuple(out)
    if not isinstance(eco, Mapping):
        raise ShipFileError(source, "economics", "must be a mapping")
    for key, value in eco.items():
        if key not in ECONOMICS_KEYS:
            raise ShipFileError(source, f"economics.{key}",
                                f"unknown key (use {', '.join(ECONOMICS_KEYS)})")
        if isinstance(value, bool) or not isinstance(value, int | float) or not 0 <= value < 1e7:
            raise ShipFileError(source, f"economics.{key}", f"must be a number in 0..1e7, "
                                f"got {value!r}")
        out.append((str(key), float(value)))
    return tuple(out)
