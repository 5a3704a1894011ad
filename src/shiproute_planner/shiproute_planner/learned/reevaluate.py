"""Re-evaluate a finished plan on another ship model: what the plan would really cost.

The plan's track and per-leg RPMs are sailed with `route.sail.sail_tracks` (each leg steered
at its waypoint, lasting distance / SOG in the weather met at its start) on ``model``, e.g.
the true (fouled) ship, giving the fuel burnt and the arrival time that ship would have.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..route.environment import Environment
from ..route.problem import RouteLimits, RouteProblem
from ..route.sail import sail_tracks


@dataclass(frozen=True)
class Outcome:
    """A plan sailed by another model."""

    fuel_t: float
    eta_s: float
    late_h: float  # arrival minus RTA [h] (negative = early)


def reevaluate(plan: Any, model: Any, sampler: Any = None) -> Outcome:
    """Sail ``plan`` (a `RoutePlan`) with ``model`` in the forecast ``sampler``."""
    lon, lat, _ = plan.track()
    rpm = plan.leg_rpm()
    e = model.ship.engine
    limits = RouteLimits(rpm_min=e.rpm_min, rpm_max=e.rpm_max)
    problem = RouteProblem(float(lon[0]), float(lat[0]), float(lon[-1]), float(lat[-1]),
                           plan.departure_s, plan.rta_s, limits, stage_s=plan.stage_s)
    ev = sail_tracks(problem, Environment(model, sampler), None, lon, lat, rpm,
                     plan.departure_s)
    eta = float(ev.eta_s[0])
    return Outcome(float(ev.fuel_t[0]), eta, (eta - plan.rta_s) / 3600.0)


