"""Errors raised by the planner library: one base class, specific subclasses naming the input."""

from __future__ import annotations


class PlannerError(Exception):
    """Base class of every error the planner library raises on purpose."""


class PortNotFoundError(PlannerError):
    """A port name, UN/LOCODE or coordinate string could not be resolved."""


class PositionOnLandError(PlannerError):
    """A port or waypoint lies on land too far from navigable water."""


class InvalidVoyageError(PlannerError):
    """Voyage inputs (times, RTA, stages, bounds) are inconsistent."""


class LandDataError(PlannerError):
    """Coastline data is missing or unreadable."""


class SeedPoolError(PlannerError):
    """The seed pool file exists but cannot be read or written."""


class UnknownMethodError(PlannerError):
    """A planning method name is not in the registry."""


class PlanCancelledError(PlannerError):
    """Planning was cancelled or superseded before any plan was available."""


class OutputError(PlannerError):
    """A plan could not be written (RTZ, GeoJSON, JSON, PNG) or fails schema validation."""


class ForecastCycleError(PlannerError, ValueError):
    """A forecast cycle's slices are out of range or inconsistent (grid, fields, times)."""


class BathymetryError(PlannerError):
    """A bathymetry grid is missing, unreadable, not a lat/lon grid or holds no depth."""


class ZoneFileError(PlannerError):
    """A no-go zone file is not GeoJSON polygons or has invalid properties."""


class RouteFileError(PlannerError):
    """A route file (RTZ, GeoJSON) to check cannot be read or has too few waypoints."""
# ---- input validation at the planner's boundaries (issue 16) ------------------------------
class StaleForecastError(ForecastCycleError):
    """A forecast cycle comes from an older model run than the cycle in force."""


class ShipStateError(PlannerError, ValueError):
    """A ship state (fix) is not finite, out of range or stamped outside the accepted window."""


class ParameterError(PlannerError, ValueError):
    """A planner parameter is outside its range (the message names it, the range and why)."""
