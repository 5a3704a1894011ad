"""Every leg a plan publishes checked at the finest coastline installed, and repaired.

After a leg is planned (approach in, the method's span, approach out; or a strait passage),
its parts are checked at GSHHG full resolution every 0.25 NM (`geo.full_land`), outside
`PORT_RADIUS_M` round its berths (harbour basins are the pilot's). A leg that touches land
gets a local detour round the obstacle (`route.land_repair`: fine navigable grid,
clearance `RepairRules.clearances_nm[0]` where there is room); its sub-legs are sailed at the
leg's RPM with the exact evaluator, and the parts after it are sailed from the new times, so
the legs planned next start when this one really ends. A span whose detour would make it
arrive later keeps its arrival time by a uniform RPM rise (stated). What is not repaired
keeps the land flag and the plan says why.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from .coastal_passages import passage_rules
from .geo.full_land import FinalLand, final_land
from .geo.ports import Port
from .route.berths import BERTH_RADIUS_M
from .route.environment import Environment
from .route.evaluation import RouteEvaluation
from .route.land_repair import RepairRules, repaired_track
from .route.passages import best_land_polygons
from .route.problem import RouteLimits, RouteProblem
from .route.sail import sail_tracks
from .seed_ga import with_land_legs

PORT_RADIUS_M = BERTH_RADIUS_M  # round a berth the land is not checked (the route check's)
INSERTED = (" gate", " entrance", " exit")  # names of points the planner inserts in a leg
KEEP_ETA_ROUNDS = 3  # RPM corrections that bring a repaired span back to its arrival time


def is_berth(port: Port, k: int, n_ports: int) -> bool:
    """True for a port the ship berths at (ends, vias), not a gate or canal point."""
    inserted = port.name.endswith(INSERTED) or port.name.startswith("turning point")
    return k in (0, n_ports - 1) or not inserted


@dataclass(frozen=True)
class RepairContext:
    """What repairing a leg needs: the environment, limits, final land test and rules."""

    env: Environment
    limits: RouteLimits
    land: FinalLand
    rules: RepairRules = field(default_factory=RepairRules)


def repair_context(env: Environment, limits: RouteLimits,
                   clearance_nm: float | None = None) -> RepairContext:
    """The context of a plan; `clearance_nm` (> 0) is the detours' preferred clearance."""
    rules = RepairRules()
    if clearance_nm:
        rules = dataclasses.replace(rules, clearances_nm=tuple(sorted(
            {clearance_nm, *rules.clearances_nm}, reverse=True)))
    return RepairContext(env, limits, final_land(), rules)


def _part_problem(part: RouteEvaluation, limits: RouteLimits, t0_s: float,
                  problem: RouteProblem | None) -> RouteProblem:
    """The part's own problem (a span's) or one like an approach's (no RTA)."""
    if problem is not None:
        return problem
    lon, lat = part.lon_deg[0], part.lat_deg[0]
    return RouteProblem(float(lon[0]), float(lat[0]), float(lon[-1]), float(lat[-1]), t0_s,
                        t0_s + 30 * 86400.0, limits)


def resail(ctx: RepairContext, part: RouteEvaluation, lon: np.ndarray, lat: np.ndarray,
           rpm: np.ndarray, depart_s: float, problem: RouteProblem | None) -> RouteEvaluation:
    """A part's (new) nodes sailed at `rpm` per leg from `depart_s` (exact evaluator; land
    is the final check's, not the optimiser's coarser one)."""
    p = _part_problem(part, ctx.limits, depart_s, problem)
    return sail_tracks(p, ctx.env, None, lon[None, :], lat[None, :], rpm[None, :], depart_s)


def _keep_arrival(ctx: RepairContext, part: RouteEvaluation, new: RouteEvaluation,
                  lon: np.ndarray, lat: np.ndarray, rpm: np.ndarray,
                  problem: RouteProblem) -> tuple[RouteEvaluation, float]:
    """The repaired span with its RPMs raised uniformly (within the ship's range) so it
    arrives when the span did before the detour; (evaluation, RPM factor)."""
    target = float(part.eta_s[0])
    t0 = float(part.time_s[0, 0])
    factor = 1.0
    for _ in range(KEEP_ETA_ROUNDS):
        late = float(new.eta_s[0]) - target
        if late <= 1.0:
            break
        factor *= (float(new.eta_s[0]) - t0) / max(target - t0, 1.0)
        scaled = np.clip(rpm * factor, problem.limits.rpm_min, problem.limits.rpm_max)
        new = resail(ctx, part, lon, lat, scaled, t0, problem)
    return new, factor


def repair_part(ctx: RepairContext, part: RouteEvaluation, depart_s: float,
                problem: RouteProblem | None, skip_start_m: float, skip_end_m: float,
                what: str) -> tuple[RouteEvaluation, list[dict]]:
    """One part checked at the final resolution and repaired; sailed again from `depart_s`
    when it was repaired or starts at another time. Returns (part, rows of what was done:
    each with its words under "text")."""
    lon, lat = part.lon_deg[0], part.lat_deg[0]
    rpm = np.asarray(part.legs["rpm"][0], dtype=float)
    new_lon, new_lat, owner, repairs, left = repaired_track(
        lon, lat, ctx.land.contains, best_land_polygons(), passage_rules(
            ctx.limits.under_keel), ctx.rules, skip_start_m, skip_end_m)
    said = [r.row(what) for r in repairs]
    moved = abs(depart_s - float(part.time_s[0, 0])) > 1e-3
    if not repairs and not moved and not left:
        return part, said
    out = part
    if repairs or moved:
        out = resail(ctx, part, new_lon, new_lat, rpm[owner], depart_s, problem)
    if repairs and problem is not None and not moved:
        out, factor = _keep_arrival(ctx, part, out, new_lon, new_lat, rpm[owner], problem)
        if factor > 1.0 + 1e-4:
            said.append({"part": what, "rpm_factor": round(factor, 5), "text": (
                f"land repair ({what}): RPM raised {100.0 * (factor - 1.0):.2f} % to keep "
                "the span's arrival time after the detour")})
    if left:
        bad = sorted({int(i) for i in np.flatnonzero(np.isin(owner, left))})
        out = with_land_legs(out, bad)
        said += [{"part": what, "stage": k + 1, "repaired": False, "text": (
            f"land repair ({what}): no detour found for stage {k + 1} (land at "
            f"{ctx.land.words}); the leg stays flagged")} for k in left]
    return out, said


def repaired_leg(ctx: RepairContext, ports: tuple[Port, Port], berths: tuple[bool, bool],
                 pre: RouteEvaluation | None, span: RouteEvaluation, problem: RouteProblem,
                 sail_post: Callable[[float], RouteEvaluation] | None,
                 given: tuple[bool, bool] = (False, False),
                 ) -> tuple[RouteEvaluation | None, RouteEvaluation, RouteEvaluation | None,
                            list[dict]]:
    """(approach in, span, approach out, statements) of a leg a -> b, each part checked
    and repaired, the later parts sailed from the times the earlier ones end; approaches
    the user gave (`given`: in, out) are sailed as given (the route check judges them)."""
    a, b = ports
    skip_a = PORT_RADIUS_M if berths[0] else 0.0
    skip_b = PORT_RADIUS_M if berths[1] else 0.0
    said: list[dict] = []
    t = float((pre or span).time_s[0, 0])
    if pre is not None:
        if not given[0]:
            pre, s = repair_part(ctx, pre, t, None, skip_a, 0.0, f"approach from {a.name}")
            said += s
        t, skip_a = float(pre.eta_s[0]), 0.0
    span, s = repair_part(ctx, span, t, problem, skip_a,
                          skip_b if sail_post is None else 0.0, f"{a.name} -> {b.name}")
    said += s
    post = sail_post(float(span.eta_s[0])) if sail_post is not None else None
    if post is not None and not given[1]:
        post, s = repair_part(ctx, post, float(post.time_s[0, 0]), None, 0.0, skip_b,
                              f"approach to {b.name}")
        said += s
    return pre, span, post, said


def land_statement(ctx: RepairContext) -> str:
    """What every plan's legs were checked with."""
    return (f"land checked at {ctx.land.words} every 0.25 NM on every leg (outside canals "
            f"and {PORT_RADIUS_M / 1000.0:g} km round berths); legs on land get a detour "
            f"{ctx.rules.clearances_nm[0]:g} NM off land where there is room")


def repaired_canal(ctx: RepairContext, name: str, lead_in: RouteEvaluation | None,
                   canal: RouteEvaluation, lead_out: RouteEvaluation | None,
                   problem: RouteProblem) -> tuple[RouteEvaluation | None, RouteEvaluation,
                                                   RouteEvaluation | None, list[dict]]:
    """A canal leg: its lead-in and lead-out (a gulf or channel sailed at sea) checked and
    repaired, the canal itself (the authority's fixed line) only sailed from the lead-in's
    new end."""
    said: list[dict] = []
    if lead_in is not None:
        lead_in, s = repair_part(ctx, lead_in, float(lead_in.time_s[0, 0]), None, 0.0, 0.0,
                                 f"lead-in to {name}")
        said += s
        t = float(lead_in.eta_s[0])
        if abs(t - float(canal.time_s[0, 0])) > 1e-3:
            canal = resail(ctx, canal, canal.lon_deg[0], canal.lat_deg[0],
                           np.asarray(canal.legs["rpm"][0], dtype=float), t, problem)
    if lead_out is not None:
        lead_out, s = repair_part(ctx, lead_out, float(canal.eta_s[0]), None, 0.0, 0.0,
                                  f"lead-out from {name}")
        said += s
    return lead_in, canal, lead_out, said
