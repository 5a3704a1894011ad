"""The optimised spans of a voyage and what each gets: its stage length and its share of the
search budget.

Straits and canals split a user's leg (Busan -> Long Beach) into spans between fixed passages
(Busan -> Tsugaru Strait, Tsugaru Strait -> Long Beach). The stages a short passage is given
(`stage_length.TARGET_STAGES`) belong to the user's leg and are shared among its spans by
time: deriving them per span gave a 36-hour span before a strait 12 stages of 2.8 h, and the
ocean span after it lost the search time those genes took. The search budget is shared among
the spans by their number of genes (two per stage: heading and RPM), the GA's work growing
with them; fixed passages (straits, canals) have none."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from .stage_length import MIN_SPAN_STAGES, TARGET_STAGES, default_stage_hours

MIN_SHARE_OF_EVEN = 0.2  # no optimised span gets less than a fifth of an even share


@dataclass(frozen=True)
class SpanPlan:
    """Per span ports[k] -> ports[k+1]: the user's leg it belongs to, the user's stage length
    [h] (None: derived by the leg set-up), the stages the set-up aims at at least, and whether
    it is optimised (not a fixed strait or canal passage)."""

    user_leg: tuple[int, ...]
    stage_hours: tuple[float | None, ...]
    optimised: tuple[bool, ...]
    target_stages: tuple[int, ...] = ()

    def genes_estimate(self, k: int, window_s: float) -> int:
        """Genes (headings and RPMs) span `k` will have over a window of `window_s` seconds."""
        if not self.optimised[k]:
            return 0
        target = self.target_stages[k] if self.target_stages else TARGET_STAGES
        stage_h = self.stage_hours[k] or default_stage_hours(window_s, target)
        return 2 * max(1, math.ceil(max(window_s, 0.0) / (stage_h * 3600.0)) - 1) + 1


def user_legs(user_ports: Sequence[Any], ports: Sequence[Any]) -> tuple[int, ...]:
    """For each span of `ports` (the user's ports with strait gates and canal ends inserted),
    the index of the user's leg it lies on (the user's ports are the same objects)."""
    out, leg = [], -1
    for k, p in enumerate(ports[:-1]):
        if k == 0 or any(p is q for q in user_ports):
            leg += 1
        out.append(max(leg, 0))
    return tuple(out)


def span_plan(user_ports: Sequence[Any], ports: Sequence[Any], fixed: set[int],
              arrivals_s: Sequence[float], depart_s: float,
              stage_hours: float | None) -> SpanPlan:
    """Stage length per span: the user's override, else derived by each span's set-up
    (`leg_stage_hours`: 12 h for a crossing, shorter for a short window or a lane round
    capes) aiming at the user's leg's TARGET_STAGES shared among its spans by time
    (`arrivals_s[k]`: planned arrival at the end of span k), at least MIN_SPAN_STAGES: the
    36-hour span of Busan -> Long Beach before the Tsugaru Strait gets 4 stages, not 12 of
    2.8 h (the ocean span after it keeps 12-hour stages). A leg of one span aims at
    TARGET_STAGES as before."""
    legs = user_legs(user_ports, ports)
    optimised = tuple(k not in fixed for k in range(len(legs)))
    hours = (float(stage_hours),) * len(legs) if stage_hours is not None else (None,) * len(legs)
    starts = [depart_s, *arrivals_s[:-1]]
    targets = []
    for k, leg in enumerate(legs):
        members = [j for j, u in enumerate(legs) if u == leg]
        if len(members) == 1:
            targets.append(TARGET_STAGES)
            continue
        whole = arrivals_s[members[-1]] - starts[members[0]]
        part = (arrivals_s[k] - starts[k]) / whole if whole > 0 else 1.0
        targets.append(max(MIN_SPAN_STAGES, round(TARGET_STAGES * part)))
    return SpanPlan(legs, hours, optimised, tuple(targets))


def budget_share(plan: SpanPlan, k: int, genes_k: int, arrivals_s: Sequence[float]) -> float:
    """Share of the budget left that span `k` (with `genes_k` genes, now set up) gets: its
    genes over those of the optimised spans left (the later ones estimated from their
    scheduled windows), and never less than a fifth of an even share (a short span still
    gets its seeds evaluated and a few generations)."""
    later = [plan.genes_estimate(j, arrivals_s[j] - arrivals_s[j - 1])
             for j in range(k + 1, len(plan.optimised))]
    total = genes_k + sum(later)
    n_left = 1 + sum(1 for g in later if g > 0)
    share = genes_k / total if total > 0 else 1.0
    return float(min(1.0, max(share, MIN_SHARE_OF_EVEN / n_left)))
