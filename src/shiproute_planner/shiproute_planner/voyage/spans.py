"""The optimised spans of a voyage and what each gets: its stage length and its share of the
search budget.

Straits and canals split a user's leg (Busan -> Long Beach) into spans between fixed passages
(Busan -> Tsugaru Strait, Tsugaru Strait -> Long Beach). The stage length is a property of the
user's passage, derived once from its whole window (`stage_length`): deriving it per span
gave a 36-hour span before a strait 12 stages of 2.8 h, and the ocean span after it lost the
search time those genes took.
The search budget is shared among the spans by their number of genes (two per stage: heading
and RPM), the GA's work growing with them; fixed passages (straits, canals) have none.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from .stage_length import default_stage_hours

MIN_SHARE_OF_EVEN = 0.2  # no optimised span gets less than a fifth of an even share


@dataclass(frozen=True)
class SpanPlan:
    """Per span ports[k] -> ports[k+1]: the user's leg it belongs to, its stage length [h]
    (None: derived by the leg set-up from its own window, the user's leg being this one span)
    and whether it is optimised (not a fixed strait or canal passage)."""

    user_leg: tuple[int, ...]
    stage_hours: tuple[float | None, ...]
    optimised: tuple[bool, ...]

    def genes_estimate(self, k: int, window_s: float) -> int:
        """Genes (headings and RPMs) span `k` will have over a window of `window_s` seconds."""
        if not self.optimised[k]:
            return 0
        stage_h = self.stage_hours[k] or default_stage_hours(window_s)
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
    """Stage length per span: the user's override, else one length per user's leg from its
    scheduled window (`arrivals_s[k]`: planned arrival at the end of span k), 12 h for a
    crossing and ~TARGET_STAGES stages for a short passage. The lane-turn rule
    (`leg_stage_hours`) is for legs that run through straits and canals; on a leg split by
    them those are fixed passages, and the turns of its spans' lanes counted near coasts
    (Cape Erimo beside the Tsugaru Strait, the Californian coast) gave Busan -> Long Beach
    8.7-hour stages and 23 t more fuel. A leg that is a single span derives its own in the
    leg set-up (the window there excludes the coastal approaches, the turn rule applies)."""
    legs = user_legs(user_ports, ports)
    optimised = tuple(k not in fixed for k in range(len(legs)))
    if stage_hours is not None:
        return SpanPlan(legs, (float(stage_hours),) * len(legs), optimised)
    hours: list[float | None] = []
    for k, leg in enumerate(legs):
        members = [j for j, u in enumerate(legs) if u == leg]
        if len(members) == 1:
            hours.append(None)
            continue
        first, last = members[0], members[-1]
        if k != first:
            hours.append(hours[first])
            continue
        start_s = depart_s if first == 0 else arrivals_s[first - 1]
        hours.append(default_stage_hours(arrivals_s[last] - start_s))
    return SpanPlan(legs, tuple(hours), optimised)


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
