"""No-go zones a voyage is planned with, and the route check every finished plan gets.

The check is the one `shiproute check` runs (land, clearance, depth/UKC, zones), on the same
coastline (the finest GSHHG installed, `geo.full_land`), berth to berth: the route between
two berths (voyage ends and port calls, not gates or canal points) is checked with
`PORT_RADIUS_M` round each berth left to the pilot, canals (fixed passages) skipped. Its
findings go into the plan's warnings; land or clearance on any checked leg, and depth or a
zone on a leg the method planned, make the plan infeasible with the finding as the reason,
so a published plan never claims a check it fails.
"""

from __future__ import annotations

import dataclasses
import itertools
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path

import numpy as np
from shiproute_core.flags import FLAG_LAND, FLAG_NAMES
from shiproute_core.geodesy import inverse

from .geo.full_land import final_land
from .geo.landmask import LandMask
from .geo.zones import Zones, load_zones
from .plan_repair import INSERTED, PORT_RADIUS_M
from .plan_types import RoutePlan
from .route.problem import RouteLimits
from .route_check import CheckResult, Violation, check_track

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


def berth_cuts(plan: RoutePlan) -> list[int]:
    """Waypoint indices of the plan's berths: its ends and the port calls between them."""
    wps = plan.waypoints
    inner = [i for i, w in enumerate(wps) if 0 < i < len(wps) - 1 and w.port
             and not w.port.endswith(INSERTED) and not w.port.startswith("turning point")]
    return [0, *inner, len(wps) - 1]


def check_berth_to_berth(plan: RoutePlan, limits: RouteLimits, clearance_nm: float = 0.0
                         ) -> CheckResult:
    """The route check of a plan, berth to berth, on the final coastline (leg numbers are
    the plan's)."""
    land = final_land()
    hs = np.nan_to_num(np.array([w.hs_m for w in plan.waypoints[:-1]]), nan=0.0)
    return berth_parts_checked(plan, lambda lon, lat, speed, a, b, skip: check_track(
        lon, lat, speed, land.contains, clearance_nm=clearance_nm, land_near=land.clipped,
        under_keel=limits.under_keel, hs_m=hs[a:b], zones=limits.zones,
        port_clearance_m=PORT_RADIUS_M, skip_legs=skip))


def berth_parts_checked(plan: RoutePlan, check: Callable[..., CheckResult]) -> CheckResult:
    """`check(lon, lat, speed_kn, a, b, skip_legs)` on each part of the plan's track between
    two berths (legs a..b; the fixed passages in it skipped), findings numbered as the
    plan's legs."""
    lon, lat, _ = plan.track()
    speed = np.array([w.stw_kn for w in plan.waypoints[:-1]])
    fixed = {k for a, b in plan.extra.get("fixed_passages", ()) for k in range(a, b)}
    found: list[Violation] = []
    notes: list[str] = []
    for a, b in itertools.pairwise(berth_cuts(plan)):
        if b <= a:
            continue
        part = check(lon[a:b + 1], lat[a:b + 1], speed[a:b], a, b,
                     frozenset(k - a for k in fixed if a <= k < b))
        found += [dataclasses.replace(v, leg=v.leg + a) for v in part.violations]
        notes += [n for n in part.notes if n not in notes]
    return CheckResult(tuple(found), tuple(notes))


def baseline_land(plan: RoutePlan) -> list[Violation]:
    """Land findings on the plan's constant-RPM baseline track at the final coastline
    (outside `PORT_RADIUS_M` round the plan's berths and along the canals the plan sails as
    fixed passages): the comparison's reference is held to the same coastline as the plan."""
    if len(plan.baseline_track) < 2:
        return []
    lat, lon = (np.array(c, dtype=float) for c in zip(*plan.baseline_track, strict=True))
    canal = {(round(w.lat_deg, 5), round(w.lon_deg, 5))
             for a, b in plan.extra.get("fixed_passages", ()) for w in plan.waypoints[a:b + 1]}
    on_canal = np.array([(round(la, 5), round(float((lo + 180.0) % 360.0 - 180.0), 5))
                         in canal for la, lo in zip(lat, lon, strict=True)])
    skip = frozenset(np.flatnonzero(on_canal[:-1] & on_canal[1:]).tolist())
    lon = np.unwrap(lon, period=360.0)
    found = check_track(lon, lat, np.full(lon.size - 1, 14.0), final_land().contains,
                        port_clearance_m=PORT_RADIUS_M, skip_legs=skip).violations
    berths = [plan.waypoints[i] for i in berth_cuts(plan)]
    b_lon = np.array([w.lon_deg for w in berths])
    b_lat = np.array([w.lat_deg for w in berths])
    out = []
    for v in found:
        _, d = inverse(np.full(b_lon.size, v.lon_deg), np.full(b_lat.size, v.lat_deg),
                       b_lon, b_lat)
        if np.min(d) > PORT_RADIUS_M:
            out.append(v)
    return out


def with_baseline_check(plan: RoutePlan) -> RoutePlan:
    """The plan with its baseline's land findings stated (and its feasibility withdrawn);
    a baseline already infeasible is not checked again (its flags are stated already)."""
    if not plan.baseline_feasible:
        return plan
    found = baseline_land(plan)
    if not found:
        return plan
    v, name = found[0], plan.baseline_method or "constant RPM"
    said = (f"baseline ({name}) touches land at {final_land().words}: {len(found)} "
            f"leg(s), first at {v.lat_deg:.3f}N {v.lon_deg:.3f}E; the fuel "
            f"comparison is against a route a ship could not sail as drawn")
    return dataclasses.replace(plan, baseline_feasible=False,
                               warnings=(*plan.warnings, said))


def checked_plan(plan: RoutePlan, land: LandMask, limits: RouteLimits,
                 clearance_nm: float = 0.0) -> RoutePlan:
    """The plan with the route check's findings in its warnings (and feasibility); the check
    runs on the finest coastline, the one the optimiser searched on with `limits.clearance`
    (`land`, the mask of ports and seeds, is not used)."""
    if len(plan.waypoints) < 2:
        return plan
    plan = with_baseline_check(plan)
    result = check_berth_to_berth(plan, limits, clearance_nm)
    found = result.violations
    warnings = list(plan.warnings)
    warnings.append(f"land checked at {final_land().words} every 0.25 NM on every leg "
                    f"(outside canals and {PORT_RADIUS_M / 1000.0:g} km round berths); "
                    f"search: {final_land().words}, {limits.clearance.words}")
    warnings += [f"route check: {v.line().strip()}" for v in found[:MAX_LISTED]]
    if len(found) > MAX_LISTED:
        warnings.append(f"route check: {len(found) - MAX_LISTED} more finding(s)")
    warnings += [f"route check: {n}" for n in result.notes]
    warnings.append(clearance_words(plan, limits))
    planned = np.zeros(len(plan.waypoints) - 1, dtype=bool)
    for a, b in plan.optimised_spans or ((0, len(planned)),):
        planned[a:b] = True
    # depth next to ports and approach ends is pilotage (dredged channels): listed, not
    # deciding; elsewhere the optimiser's own UKC constraint has decided already. Land
    # decides on every leg checked (approaches and straits are repaired like the spans).
    bad = [v for v in found if v.kind == "land" or (planned[v.leg] and v.kind != "depth")]
    plan = with_clearance_reason(plan, found)
    if bad and plan.feasible:
        return dataclasses.replace(
            plan, warnings=tuple(warnings), feasible=False, infeasible_reasons=tuple(
                dict.fromkeys(f"route check: {v.kind} on leg {v.leg}" for v in bad)))
    return dataclasses.replace(plan, warnings=tuple(warnings))


CLEARANCE_REASON = ("closer to land than the clearance rule (the route check finds no land at "
                    "full resolution: see the clearance check)")


def with_clearance_reason(plan: RoutePlan, found: Iterable[Violation]) -> RoutePlan:
    """The plan with its search's land verdict named for what it is when the route check
    finds no land on any leg: the search counts legs closer to land than its clearance rule
    with those on land (one constraint), so "crosses land" would misstate a shortfall."""
    land = FLAG_NAMES[FLAG_LAND]
    if plan.feasible or land not in plan.infeasible_reasons or any(
            v.kind == "land" for v in found):
        return plan
    return dataclasses.replace(plan, infeasible_reasons=tuple(
        CLEARANCE_REASON if r == land else r for r in plan.infeasible_reasons))


def clearance_shortfalls(plan: RoutePlan, limits: RouteLimits) -> list[tuple[int, float, float]]:
    """(leg, lat, lon at the leg's start) of the optimised spans' legs closer to land than the
    search's clearance rule, tight water included (`route.land_walk` in check mode: level-1
    lower bounds of the distance, so a leg keeping the rule to ~0.7 NM may be listed)."""
    from .route.land_walk import LandWalk
    from .route.problem import RouteProblem

    lon, lat, t = plan.track()
    out = []
    for a, b in plan.optimised_spans or ((0, len(plan.waypoints) - 1),):
        if b <= a:
            continue
        span = RouteProblem(float(lon[a]), float(lat[a]), float(lon[b]), float(lat[b]),
                            float(t[a]), max(float(t[b]), float(t[a]) + 3600.0), limits)
        got = LandWalk(span, search=False).segments(lon[a:b], lat[a:b], lon[a + 1:b + 1],
                                                    lat[a + 1:b + 1])
        out += [(a + int(k), float(lat[a + k]), float(lon[a + k])) for k in np.flatnonzero(got)]
    return out


def clearance_words(plan: RoutePlan, limits: RouteLimits) -> str:
    """The clearance the optimised spans keep, measured with the search's rule (never silent:
    met, or the legs that fall short)."""
    short = clearance_shortfalls(plan, limits)
    rule = limits.clearance
    if not short:
        return f"clearance check: the optimised spans keep the search's rule ({rule.words})"
    leg, la, lo = short[0]
    return (f"clearance check: {len(short)} leg(s) of the optimised spans come closer to land "
            f"than the rule ({rule.open_sea_nm:g} NM open sea / {rule.approach_nm:g} NM near "
            f"span ends and in narrow water, measured on full-resolution distance lower "
            f"bounds), first leg {leg} from {la:.3f}N {lo:.3f}E; in water narrower than twice "
            f"the clearance (e.g. a strait) no route can keep it: check the chart")
