"""Real plans for tests and `bench display`: Busan -> Long Beach through the March storm.

Made by the real planner (`test/make_plan_fixtures.py`: the departure plan on cycle
`storm_march`, the re-plan 24 h later on `storm_march_cycle2`, the departure plan on the
20-member `storm_march_ensemble` under CVaR 0.9 with its spread) and stored field by field, so
they are published through the planner's own message converters.
"""

from __future__ import annotations

import json
from importlib import resources
from typing import Any

SAMPLE_PLANS = ("plan_cycle1", "plan_cycle2", "plan_ensemble")


def load_sample_plan(name: str) -> Any:
    """A stored sample as a planner `RoutePlan` (every waypoint field as planned)."""
    from shiproute_planner.plan_types import RoutePlan, Waypoint

    if name not in SAMPLE_PLANS:
        raise ValueError(f"no sample plan {name!r}; have {', '.join(SAMPLE_PLANS)}")
    text = (resources.files("shiproute_display") / "sample_plans" / f"{name}.json").read_text()
    d = json.loads(text)
    d["waypoints"] = tuple(Waypoint(**w) for w in d["waypoints"])
    for key in ("infeasible_reasons", "ports", "warnings", "leg_rtas_s"):
        d[key] = tuple(d.get(key, ()))
    for key in ("fuel_quantiles_t", "eta_quantiles_s"):
        d[key] = tuple(d.get(key, ()))
    for key in ("baseline_track", "optimised_spans", "leg_hs_spread_m", "leg_wind_spread_m_s"):
        d[key] = tuple(tuple(p) for p in d.get(key, ()))
    return RoutePlan(**d)
