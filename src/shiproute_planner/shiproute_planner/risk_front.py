"""The trade-off a risk-aware search saw: the best risk measure it found at each probability
of meeting seas above the ship's limit, so the choice follows the user's bound and the plan
can say what a lower exposure would have cost (or saved).

Every candidate the risk GA evaluates on the members is offered to a `RiskFront`. One whose
only violations are member-decided chance events (Hs, the other sea-keeping limits,
lateness) is kept when it is the best (lowest risk measure) yet seen for its pair of
probabilities (P(Hs > limit), P(another sea-keeping limit)) and its lateness verdict against
the bound; with M members there are at most (M + 1)^2 x 2 such cells. Its Pareto front over
(P(Hs > limit), risk measure) is what the plan states.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .route.fast_eval import FastEvaluator
from .route.member_eval import CHANCE_TOLERANCE, MemberOutcomes, risk_evaluate_outcomes
from .route.risk import RiskSpec, weighted_quantile

PROBABILITY_DIGITS = 9  # member weights summed in another order agree to this many digits
FRONT_POINTS_SAID = 6  # front points written into the plan's warning


@dataclass(frozen=True)
class FrontPoint:
    """The best candidate seen at one exposure: its probabilities, risk measure and P90."""

    p_hs: float
    p_sea_keeping: float
    p_late: float
    risk: float  # the risk measure of the members' objective
    p90_fuel_t: float  # the members' P90 of the optimised span's fuel
    genes: np.ndarray

    @property
    def exposure(self) -> float:
        """The smallest P(Hs > limit) bound this candidate meets: the other sea-keeping
        limits are held to the same bound (`route.member_eval.chance_excess`)."""
        return max(self.p_hs, self.p_sea_keeping)


@dataclass
class RiskFront:
    """Best candidate per (P(Hs), P(sea-keeping), on time within the bound) cell."""

    spec: RiskSpec
    cells: dict[tuple[float, float, bool], FrontPoint] = field(default_factory=dict)

    def offer(self, x: np.ndarray, out: MemberOutcomes, risk: np.ndarray) -> None:
        """Keep each candidate of genes `x` (pop, n) that is free of every violation a
        member does not decide alone (land, depth, zones, ...) and best in its cell."""
        free = out.weights @ out.other_violation <= 0.0
        if not free.any():
            return
        p_hs = np.round(out.probability(out.hs_exceeded), PROBABILITY_DIGITS)
        p_sk = np.round(out.probability(out.sea_keeping), PROBABILITY_DIGITS)
        p_late = np.round(out.probability(out.late), PROBABILITY_DIGITS)
        on_time = p_late <= self.spec.p_late_max + CHANCE_TOLERANCE
        for k in np.flatnonzero(free & np.isfinite(risk)):
            key = (float(p_hs[k]), float(p_sk[k]), bool(on_time[k]))
            held = self.cells.get(key)
            if held is None or risk[k] < held.risk:
                p90 = float(weighted_quantile(out.fuel_t[:, k:k + 1], out.weights, 0.9)[0])
                self.cells[key] = FrontPoint(key[0], key[1], float(p_late[k]),
                                             float(risk[k]), p90, x[k].copy())

    def front(self, on_time_only: bool = True) -> list[FrontPoint]:
        """Pareto front over (exposure, risk measure), lowest exposure first, the exposure
        being the smallest P(Hs > limit) bound a candidate meets (`FrontPoint.exposure`);
        with `on_time_only` only candidates that meet the lateness bound."""
        points = sorted((p for (_, _, ok), p in self.cells.items() if ok or not on_time_only),
                        key=lambda p: (p.exposure, p.risk))
        kept: list[FrontPoint] = []
        for p in points:
            if not kept or p.risk < kept[-1].risk:
                kept.append(p)
        return kept

    def within_bounds(self) -> list[FrontPoint]:
        """Candidates meeting every chance bound of the spec, best risk measure first."""
        cap = self.spec.p_hs_max + CHANCE_TOLERANCE
        ok = [p for (_, _, on_time), p in self.cells.items() if on_time and p.exposure <= cap]
        return sorted(ok, key=lambda p: p.risk)


def front_note(front: list[FrontPoint], spec: RiskSpec, chosen_p_hs: float | None,
               highest_seen: float | None = None) -> str:
    """The plan's sentence on the trade-off the search saw: the front's points and what a
    lower exposure costs, or that there was none (the lowest exposure seen also the best,
    `highest_seen` the highest on-time exposure seen); empty without any front."""
    if not front:
        return ""
    head = (f"risk trade-off seen by the search on the optimised span (P(Hs or another "
            f"sea-keeping limit exceeded) -> {spec.label} of the objective, on time within "
            f"P(late) <= {spec.p_late_max:g}): ")
    chosen = "" if chosen_p_hs is None else f"; chosen at P(Hs > limit) {chosen_p_hs:.2f}"
    asked = f"; asked P(Hs > limit) <= {spec.p_hs_max:g}{chosen}"
    if len(front) == 1:
        p = front[0]
        best = f"{spec.label} {p.risk:.1f}, P90 fuel {p.p90_fuel_t:.1f} t"
        if highest_seen is None or highest_seen <= p.exposure:
            return (f"{head}none: every route seen had P(Hs > limit) {p.exposure:.2f} "
                    f"({best}){asked}")
        return (f"{head}none: the lowest P(Hs > limit) seen, {p.exposure:.2f}, is also the best "
                f"({best}); the routes seen up to {highest_seen:.2f} cost more{asked}")
    step = max(1, -(-len(front) // FRONT_POINTS_SAID))
    shown = front[::step]
    if shown[-1] is not front[-1]:
        shown.append(front[-1])
    pts = ", ".join(f"{p.exposure:.2f} -> {p.risk:.1f} (P90 fuel {p.p90_fuel_t:.1f} t)"
                    for p in shown)
    lo, hi = front[0], front[-1]
    cost = (f"; lowering it from {hi.exposure:.2f} to {lo.exposure:.2f} costs "
            f"{lo.risk - hi.risk:+.1f} in {spec.label} and {lo.p90_fuel_t - hi.p90_fuel_t:+.1f} t "
            "at P90")
    return f"{head}{pts}{cost}{asked}"


def front_first(front: RiskFront, pop: np.ndarray, keep: int = 4) -> np.ndarray:
    """Final candidates: the `keep` best of the front within the bounds, then `pop`."""
    best = [p.genes for p in front.within_bounds()[:keep]]
    return np.concatenate([np.asarray(best), pop]) if best else pop


def front_statement(fast: FastEvaluator, spec: RiskSpec, front: RiskFront,
                    chosen: np.ndarray) -> list[str]:
    """The plan's trade-off sentence, with the chosen genes' own P(Hs > limit)."""
    _, out = risk_evaluate_outcomes(fast, spec, chosen[None, :])
    seen = [p.exposure for (_, _, on_time), p in front.cells.items() if on_time]
    note = front_note(front.front(), spec, float(out.probability(out.hs_exceeded)[0]),
                      max(seen, default=None))
    return [note] if note else []
