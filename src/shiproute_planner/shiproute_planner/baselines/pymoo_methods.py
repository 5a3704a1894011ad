"""NSGA-II, SPEA2 and PSO from pymoo on the seed GA's gene encoding, with or without seeds.

The problem is the planner's own population evaluator: genes (first heading, heading changes,
one RPM per stage) in, fuel, ETA and constraint violations out, one vectorised call per
generation. "Seeded" variants put the planner's seeds (sea lane, great circle at the RTA
RPM, pool) into the first population exactly as the seed GA does; unseeded variants start
from pymoo's own random sampling within the gene bounds, as the original algorithms would.
Budgets are counted in route evaluations so every algorithm gets the same number.
The two-objective NSGA-II minimises (ETA, fuel) without the RTA constraint (ETAs beyond the
RTA + 48 h count as violations, so the front stays in the window of interest) and returns
its Pareto set; the route chosen is the least-fuel member arriving by the RTA.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from pymoo.algorithms.moo.nsga2 import NSGA2
from pymoo.algorithms.moo.spea2 import SPEA2
from pymoo.algorithms.soo.nonconvex.pso import PSO
from pymoo.core.problem import Problem
from pymoo.operators.sampling.rnd import FloatRandomSampling
from pymoo.optimize import minimize
from pymoo.termination import get_termination

from .errors import BaselineConfigError

# genes (n_pop, n_var) -> fuel_t (n_pop,), eta_s (n_pop,), violation (n_pop, n_con) >= 0,
# rta_violation (n_pop,) >= 0: the part of the violation that is lateness alone
GeneEvaluation = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]
GeneEvaluator = Callable[[np.ndarray], GeneEvaluation]

ALGORITHMS = ("nsga2", "spea2", "pso")
# the two-objective front is kept to ETAs up to this long after the RTA (as 3DDP's window)
PARETO_LATE_WINDOW_S = 48 * 3600.0


@dataclass(frozen=True)
class PymooResult:
    """Best genes found, their fuel, evaluations used and (two-objective) the Pareto set."""

    genes: np.ndarray
    fuel_t: float
    feasible: bool
    evaluations: int
    pareto_eta_s: np.ndarray
    pareto_fuel_t: np.ndarray


class _GeneProblem(Problem):
    """pymoo problem over gene arrays; constraints as aggregated violations (<= 0 feasible)."""

    def __init__(self, evaluate: GeneEvaluator, lower: np.ndarray, upper: np.ndarray,
                 two_objective: bool, eta_limit_s: float = np.inf) -> None:
        self._evaluate_genes = evaluate
        self._two = two_objective
        self._eta_limit_s = eta_limit_s
        super().__init__(n_var=lower.size, n_obj=2 if two_objective else 1, n_ieq_constr=1,
                         xl=lower, xu=upper)

    def _evaluate(self, X: np.ndarray, out: dict, *args: object, **kwargs: object) -> None:
        fuel, eta, viol, rta_viol = self._evaluate_genes(np.asarray(X, dtype=float))
        total = np.sum(viol, axis=1) if viol.ndim == 2 else np.asarray(viol)
        if self._two:
            out["F"] = np.column_stack([eta, fuel])
            beyond_h = np.maximum(0.0, eta - self._eta_limit_s) / 3600.0
            out["G"] = (total - rta_viol + beyond_h)[:, None]
        else:
            out["F"] = fuel[:, None]
            out["G"] = total[:, None]


def _algorithm(name: str, pop_size: int, sampling: object) -> object:
    if name == "nsga2":
        return NSGA2(pop_size=pop_size, sampling=sampling, eliminate_duplicates=True)
    if name == "spea2":
        return SPEA2(pop_size=pop_size, sampling=sampling, eliminate_duplicates=True)
    if name == "pso":
        return PSO(pop_size=pop_size, sampling=sampling)
    raise BaselineConfigError(f"algorithm {name!r} is not one of {', '.join(ALGORITHMS)}")


def run_pymoo(
    name: str,
    evaluate: GeneEvaluator,
    lower: np.ndarray,
    upper: np.ndarray,
    n_evaluations: int | None,
    rng: np.random.Generator,
    seeds: np.ndarray | None = None,
    pop_size: int = 50,
    two_objective: bool = False,
    rta_s: float | None = None,
    time_s: float | None = None,
) -> PymooResult:
    """Run one pymoo algorithm for `n_evaluations` route evaluations (or `time_s` of wall time
    when `n_evaluations` is None) and return its best route."""
    if two_objective and name != "nsga2":
        raise BaselineConfigError("the two-objective variant is defined for NSGA-II only")
    if n_evaluations is None:
        if time_s is None:
            raise BaselineConfigError("give n_evaluations or time_s")
        termination: object = get_termination("time", max(float(time_s), 1e-3))
    elif n_evaluations < pop_size:
        raise BaselineConfigError(f"n_evaluations={n_evaluations} is below pop_size={pop_size}")
    else:
        termination = ("n_eval", int(n_evaluations))
    lower, upper = np.asarray(lower, float), np.asarray(upper, float)
    eta_limit = (rta_s + PARETO_LATE_WINDOW_S) if (two_objective and rta_s is not None) else np.inf
    problem = _GeneProblem(evaluate, lower, upper, two_objective, eta_limit)
    if seeds is not None and len(seeds):
        s = np.clip(np.atleast_2d(np.asarray(seeds, float))[:pop_size], lower, upper)
        fill = rng.uniform(lower, upper, size=(pop_size - s.shape[0], lower.size))
        sampling: object = np.vstack([s, fill])
    else:
        sampling = FloatRandomSampling()
    algo = _algorithm(name, pop_size, sampling)
    with np.errstate(invalid="ignore", divide="ignore"):  # SPEA2 normalises a 1-point front
        res = minimize(problem, algo, termination,
                       seed=int(rng.integers(2**31 - 1)), verbose=False)
    evaluations = int(res.algorithm.evaluator.n_eval)
    pop = res.pop if res.pop is not None else res.opt
    X = np.atleast_2d(pop.get("X"))
    F = np.atleast_2d(pop.get("F"))
    G = np.atleast_2d(pop.get("G"))[:, 0]
    pareto_eta = pareto_fuel = np.zeros(0)
    if two_objective:
        if rta_s is None:
            raise BaselineConfigError("the two-objective variant needs rta_s to choose its route")
        opt = res.opt if res.opt is not None else pop
        o_F = np.atleast_2d(opt.get("F"))
        o_ok = np.atleast_2d(opt.get("G"))[:, 0] <= 0
        order = np.argsort(o_F[o_ok, 0])
        pareto_eta, pareto_fuel = o_F[o_ok, 0][order], o_F[o_ok, 1][order]
        fuel = F[:, 1]
        lateness = np.maximum(F[:, 0] - rta_s, 0.0)
        total = np.maximum(G, 0.0) + lateness
    else:
        fuel = F[:, 0]
        total = np.maximum(G, 0.0)
    feasible = total <= 0
    if feasible.any():
        idx = np.flatnonzero(feasible)
        best = int(idx[np.argmin(fuel[idx])])
    else:
        best = int(np.argmin(total))
    return PymooResult(X[best].copy(), float(fuel[best]), bool(feasible[best]), evaluations,
                       pareto_eta, pareto_fuel)
