"""What every baseline returns: one evaluated route plus search effort and optional Pareto front."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..route.evaluation import RouteEvaluation


@dataclass(frozen=True)
class BaselineResult:
    """One method's route, evaluated by the planner's evaluator (population of one)."""

    method: str
    evaluation: RouteEvaluation
    compute_s: float
    rpm_varied: bool
    route_evaluations: int = 0  # whole routes evaluated (metaheuristics, RPM fits)
    leg_evaluations: int = 0  # single legs sailed by graph searches
    pareto_eta_s: np.ndarray | None = field(default=None, repr=False)
    pareto_fuel_t: np.ndarray | None = field(default=None, repr=False)
    genes: np.ndarray | None = field(default=None, repr=False)
    notes: tuple[str, ...] = ()

    @property
    def tfoc_t(self) -> float:
        return float(self.evaluation.fuel_t[0])

    @property
    def feasible(self) -> bool:
        return bool(self.evaluation.feasible[0])
