"""No-go zones a voyage is planned with, and the route check every finished plan gets.

The check is the one `shiproute check` runs (land, clearance, depth/UKC, zones), here on the
planner's own land mask (GSHHG at its resolution, exact near coasts): its findings go into
the plan's warnings, and one on a leg the method planned (not a fixed approach) makes the
plan infeasible with the finding as the reason, so a published plan never claims a check
it fails.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from .geo.landmask import LandMask
from .geo.zones import Zones, load_zones
from .plan_types import RoutePlan
from .route.problem import RouteLimits
from .route_check import check_track

MAX_LISTED = 8  # findings listed one by one in the warnings; the rest counted


def zone_limits(limits: RouteLimits, zones: Sequence[str | Path] | Zones | None
                ) -> tuple[RouteLimits, list[str]]:
    """Route limits with the zones (files or a `Zones`) and the plan's words on them."""
    if zones is None or (not isinstance(zones, Zones) and not zones):
        return limits, []
    if not isinstance(zones, Zones):
        parts = [load_zones(p) for p in zones]
        zones = Zones(tuple(z for p in parts for z in p.zones), ", ".join(map(str, zones)))
    hard = sum(z.hard for z in zones.zones)
    note = (f"no-go zones from {zones.source or 'the request'}: {hard} hard, "
            f"{len(zones.zones) - hard} avoid-if-possible")
    return dataclasses.replace(limits, zones=zones), [note]


def checked_plan(plan: RoutePlan, land: LandMask, limits: RouteLimits,
                 clearance_nm: float = 0.0) -> RoutePlan:
    """The plan with the route check's findings in its warnings (and feasibility)."""
    if len(plan.waypoints) < 2:
        return plan
    lon, lat, _ = plan.track()
    wps = plan.waypoints[:-1]
    speed = np.array([w.stw_kn for w in wps])
    hs = np.nan_to_num(np.array([w.hs_m for w in wps]), nan=0.0)
    result = check_track(lon, lat, speed, land.is_land, clearance_nm=clearance_nm,
                         land_near=land.exact.clipped, under_keel=limits.under_keel,
                         hs_m=hs, zones=limits.zones,
                         skip_legs=frozenset(k for a, b in plan.extra.get("fixed_passages", ())
                                             for k in range(a, b)))
    found = result.violations
    warnings = list(plan.warnings)
    warnings += [f"route check: {v.line().strip()}" for v in found[:MAX_LISTED]]
    if len(found) > MAX_LISTED:
        warnings.append(f"route check: {len(found) - MAX_LISTED} more finding(s)")
    warnings += [f"route check: {n}" for n in result.notes]
    planned = np.zeros(len(wps), dtype=bool)
    for a, b in plan.optimised_spans or ((0, len(wps)),):
        planned[a:b] = True
    # depth next to ports and approach ends is pilotage (dredged channels): listed, not
    # deciding; elsewhere the optimiser's own UKC constraint has decided already
    bad = [v for v in found if planned[v.leg] and v.kind != "depth"]
    if bad and plan.feasible:
        return dataclasses.replace(
            plan, warnings=tuple(warnings), feasible=False, infeasible_reasons=tuple(
                dict.fromkeys(f"route check: {v.kind} on leg {v.leg}" for v in bad)))
    return dataclasses.replace(plan, warnings=tuple(warnings))
