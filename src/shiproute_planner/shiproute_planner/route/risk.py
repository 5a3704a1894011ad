"""Risk measures over ensemble members and the chance constraints of a risk-aware plan.

A candidate sailed on M members has M values of its objective (fuel, time, cost, ...);
a risk measure reduces them to the one number the GA minimises: `mean` (expected value),
`cvar:ALPHA` (conditional value at risk: the expected value of the worst 1 - ALPHA share of
the members' probability, Rockafellar & Uryasev, J. Risk 2(3), 2000) or `worst` (the maximum).
Chance constraints bound the probability (member weight) that the route meets a significant
wave height above the ship's limit anywhere along it, and that it arrives late (a member's
delay counted after heave-to and the propeller-law recovery of `route.heavy_seas`, so late
means even MCR cannot make the RTA): P <= p_max, with p_max = 0 (the default) asking it of
every member.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError

RISK_MEASURES = ("mean", "cvar", "worst")
DEFAULT_CVAR_ALPHA = 0.9


@dataclass(frozen=True)
class RiskSpec:
    """A risk measure and the chance-constraint bounds (probabilities in 0..1)."""

    measure: str = "mean"
    alpha: float = DEFAULT_CVAR_ALPHA
    p_hs_max: float = 0.0
    p_late_max: float = 0.0

    @property
    def label(self) -> str:
        """The measure as the user writes it (`mean`, `cvar:0.9`, `worst`)."""
        return f"cvar:{self.alpha:g}" if self.measure == "cvar" else self.measure


def check_probability(name: str, value: object) -> float:
    """`value` as a probability in [0, 1], else ParameterError naming `name`."""
    if isinstance(value, bool) or not isinstance(value, int | float) or not (
            math.isfinite(value) and 0.0 <= value <= 1.0):
        raise ParameterError(f"{name} must be a probability in 0..1, got {value!r}")
    return float(value)


def parse_risk(text: str, p_hs_max: float | None = None,
               p_late_max: float | None = None) -> RiskSpec:
    """`mean`, `worst` or `cvar:ALPHA` (0 < ALPHA < 1; `cvar` alone: 0.9) with the chance
    bounds (None: 0), or ParameterError saying what is wrong."""
    word, _, arg = str(text).strip().lower().partition(":")
    if word not in RISK_MEASURES:
        raise ParameterError(f"risk measure {text!r} is unknown: use mean, cvar:ALPHA "
                             "(e.g. cvar:0.9) or worst")
    alpha = DEFAULT_CVAR_ALPHA
    if arg and word != "cvar":
        raise ParameterError(f"risk measure {text!r}: only cvar takes a level (cvar:0.9)")
    if arg:
        try:
            alpha = float(arg)
        except ValueError:
            raise ParameterError(f"risk measure {text!r}: the CVaR level {arg!r} is not a "
                                 "number") from None
        if not (0.0 < alpha < 1.0):
            raise ParameterError(f"risk measure {text!r}: the CVaR level must lie strictly "
                                 f"between 0 and 1 (0.9 = the worst 10 %), got {alpha:g}")
    return RiskSpec(word, alpha,
                    check_probability("p_hs_max", 0.0 if p_hs_max is None else p_hs_max),
                    check_probability("p_late_max", 0.0 if p_late_max is None else p_late_max))


def weighted_quantile(values: np.ndarray, weights: np.ndarray, q: float) -> np.ndarray:
    """Per column of `values` (M, n): the smallest member value whose cumulative weight
    reaches `q` (the inverse of the members' step distribution function)."""
    order = np.argsort(values, axis=0, kind="stable")
    v = np.take_along_axis(values, order, axis=0)
    c = np.cumsum(weights[order], axis=0)
    k = np.argmax(c >= q - 1e-12, axis=0)
    return v[k, np.arange(values.shape[1])]


def cvar(values: np.ndarray, weights: np.ndarray, alpha: float) -> np.ndarray:
    """CVaR_alpha per column of `values` (M, n): the weighted mean over the upper 1 - alpha
    of the probability, members split at the boundary."""
    order = np.argsort(values, axis=0, kind="stable")
    v = np.take_along_axis(values, order, axis=0)
    w = weights[order]
    hi = np.cumsum(w, axis=0)
    lo = hi - w
    share = np.clip(hi - np.maximum(lo, alpha), 0.0, None)
    return np.asarray((share * v).sum(axis=0) / (1.0 - alpha))


def risk_value(values: np.ndarray, weights: np.ndarray, spec: RiskSpec) -> np.ndarray:
    """The risk measure of `spec` per column of member values (M, n)."""
    if spec.measure == "worst":
        return np.asarray(values.max(axis=0))
    if spec.measure == "cvar":
        return cvar(values, weights, spec.alpha)
    return np.asarray(weights @ values)
