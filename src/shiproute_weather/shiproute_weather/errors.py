"""Errors raised by the forecast library; each message names the input and what is wrong."""

from __future__ import annotations


class WeatherError(Exception):
    """Base class of every error raised by shiproute_weather."""


class ForecastFileError(WeatherError):
    """A forecast file cannot be opened or decoded (missing, corrupt, truncated, unknown format)."""

    def __init__(self, path: str, reason: str) -> None:
        super().__init__(f"{path}: {reason}")
        self.path = path
        self.reason = reason


class MissingVariableError(WeatherError):
    """A file or dataset lacks a variable that is required."""

    def __init__(self, path: str, variable: str, expected: str) -> None:
        super().__init__(f"{path}: variable {variable!r} missing; expected {expected}")
        self.path = path
        self.variable = variable


class VariableUnitsError(WeatherError):
    """A variable carries units that cannot be converted to the canonical SI units."""

    def __init__(self, path: str, variable: str, units: str, expected: str) -> None:
        super().__init__(
            f"{path}: variable {variable!r} has units {units!r}; expected units convertible to "
            f"{expected!r}"
        )
        self.path = path
        self.variable = variable


class ValueRangeError(WeatherError):
    """A variable holds values outside its physical range."""

    def __init__(self, path: str, variable: str, found: str, expected: str) -> None:
        super().__init__(f"{path}: variable {variable!r} {found}; expected {expected}")
        self.path = path
        self.variable = variable


class GridError(WeatherError):
    """Coordinates are missing, irregular, or inconsistent with the canonical grid contract."""

    def __init__(self, path: str, reason: str) -> None:
        super().__init__(f"{path}: {reason}")
        self.path = path


class ScenarioError(WeatherError):
    """An unknown scenario name or a scenario that cannot be built."""


class SliceError(WeatherError):
    """A forecast slice (message or dict) is inconsistent (sizes, grid, cycle)."""


class PackingError(WeatherError):
    """A field cannot be put into (or read back from) the 16-bit simple packing of the wire."""

    def __init__(self, field: str, reason: str) -> None:
        super().__init__(f"field {field!r}: {reason}")
        self.field = field


class ForecastCoverageError(WeatherError):
    """A forecast does not cover the time (or place) it is asked for at all."""


class SpoolError(WeatherError):
    """The weather node's slice spool cannot store or give back a slice (disk full, short read)."""
