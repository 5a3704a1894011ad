"""Unit conversion to the canonical SI units (speeds m/s, heights m, periods s, angles degrees)."""

from __future__ import annotations

import re

from shiproute_core.units import M_S_PER_KNOT

from ..errors import VariableUnitsError

# canonical units -> {normalised source unit: factor to canonical}
_FACTORS: dict[str, dict[str, float]] = {
    "m s-1": {
        "m s-1": 1.0, "m/s": 1.0, "m s**-1": 1.0, "ms-1": 1.0, "meter second-1": 1.0,
        "meters/second": 1.0, "metre/second": 1.0, "meters per second": 1.0,
        "m.s-1": 1.0, "mps": 1.0,
        "cm s-1": 0.01, "cm/s": 0.01, "cm s**-1": 0.01, "centimeters/second": 0.01,
        "knots": M_S_PER_KNOT, "knot": M_S_PER_KNOT, "kt": M_S_PER_KNOT,
        "kts": M_S_PER_KNOT, "kn": M_S_PER_KNOT,
        "km h-1": 1 / 3.6, "km/h": 1 / 3.6, "kph": 1 / 3.6, "km h**-1": 1 / 3.6,
    },
    "m": {"m": 1.0, "meter": 1.0, "meters": 1.0, "metre": 1.0, "metres": 1.0,
          "cm": 0.01, "ft": 0.3048, "feet": 0.3048},
    "s": {"s": 1.0, "sec": 1.0, "second": 1.0, "seconds": 1.0},
    "s-1": {"s-1": 1.0, "hz": 1.0, "1/s": 1.0, "s**-1": 1.0, "1 s-1": 1.0, "hertz": 1.0},
    "degree": {"degree": 1.0, "degrees": 1.0, "deg": 1.0, "degree true": 1.0,
               "degrees true": 1.0, "degree_true": 1.0, "degrees_true": 1.0, "°": 1.0,
               "degrees_north": 1.0, "degree_north": 1.0, "degrees_east": 1.0,
               "rad": 57.29577951308232, "radian": 57.29577951308232,
               "radians": 57.29577951308232},
}


def normalise_units(units: str) -> str:
    """Lower-case, trim, collapse spaces, drop a trailing '(nautical)' style comment."""
    u = re.sub(r"\s+", " ", units.strip().lower())
    return re.sub(r"\s*\(.*\)$", "", u)


def si_factor(units: str | None, canonical: str, where: str, variable: str) -> float:
    """Multiplier from `units` to `canonical`; missing units are taken as already canonical."""
    if units is None or units.strip() == "" or units.strip() == "1":
        return 1.0
    table = _FACTORS[canonical]
    factor = table.get(normalise_units(units))
    if factor is None:
        raise VariableUnitsError(where, variable, units, canonical)
    return factor
