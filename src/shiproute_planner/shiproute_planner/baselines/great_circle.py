"""Great circle (or the sea lane where it touches land) at the constant RPM meeting the RTA.

The same baseline the planner shows beside every plan (`method_context.baseline_track` and
`route.rta.constant_rpm_for_rta`), wrapped as a comparison row.
"""

from __future__ import annotations

import time

from ..method_context import baseline_track
from ..route.rta import constant_rpm_for_rta
from .inputs import BaselineInputs
from .result import BaselineResult

RTA_FIT_EVALUATIONS = 24 * 3 + 1  # route.rta defaults: n_try x rounds, plus the final one


def run_great_circle(inp: BaselineInputs) -> BaselineResult:
    """Great circle / sea lane at the lowest constant RPM that arrives by the RTA."""
    t0 = time.perf_counter()
    kind, lon, lat = baseline_track(inp.problem, inp.land)
    rpm, ev = constant_rpm_for_rta(inp.problem, inp.env, inp.land, lon, lat)
    return BaselineResult("great_circle", ev, time.perf_counter() - t0, False,
                          route_evaluations=RTA_FIT_EVALUATIONS,
                          notes=(f"track: {kind}", f"constant rpm {rpm:.2f}"))
