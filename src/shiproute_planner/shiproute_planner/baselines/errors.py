"""Errors of the baseline methods, under the planner's base error so callers catch one type."""

from __future__ import annotations

from ..errors import PlannerError


class BaselineError(PlannerError):
    """Base class of the errors the baseline methods raise."""


class BaselineGridError(BaselineError):
    """A search grid cannot be built for the voyage (too small, ports cut off by land)."""


class NoRouteFoundError(BaselineError):
    """A search exhausted its graph without reaching the arrival port."""


class BaselineConfigError(BaselineError):
    """A baseline parameter is out of range or inconsistent with the voyage."""
