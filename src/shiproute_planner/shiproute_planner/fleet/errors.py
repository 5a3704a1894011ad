"""Errors of fleet planning: one base class (a PlannerError), specific ones naming the input."""

from __future__ import annotations

from ..errors import PlannerError


class FleetError(PlannerError):
    """Base class of the fleet planner's deliberate errors."""


class VoyageFileError(FleetError):
    """The voyages file cannot be read at all (missing, unknown format, no required column)."""


class SchedulerUnreachableError(FleetError):
    """No Dask scheduler answers at the given address."""
