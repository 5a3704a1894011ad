"""Errors raised by the ship performance model (one base class, specific subclasses)."""

from __future__ import annotations


class ShipModelError(Exception):
    """Base class of every error raised by ``shiproute_planner.ship``."""


class ShipFileError(ShipModelError):
    """A ship file is missing, unreadable or invalid (message names file, key and problem)."""

    def __init__(self, source: str, key: str, problem: str) -> None:
        self.source = source
        self.key = key
        self.problem = problem
        where = f"{source}: key '{key}'" if key else source
        super().__init__(f"{where}: {problem}")


class UnknownShipError(ShipModelError):
    """A ship name is neither a bundled ship nor an existing file."""


class InputRangeError(ShipModelError):
    """An input array holds values outside the model's valid range (names input and range)."""

    def __init__(self, name: str, problem: str) -> None:
        self.name = name
        super().__init__(f"input '{name}': {problem}")


class ProfileError(ShipModelError):
    """A performance-profile NetCDF file is missing variables or has an invalid grid."""


class LoadingConditionError(ShipModelError):
    """A loading condition that the ship file does not have or drafts the hull cannot take."""
