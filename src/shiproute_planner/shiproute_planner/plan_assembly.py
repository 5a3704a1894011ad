"""A voyage's legs put together into one frozen `RoutePlan`."""

from __future__ import annotations

import dataclasses
import uuid

from shiproute_core.units import M_PER_NM

from .plan_types import RoutePlan, Waypoint, reasons_of, waypoints_from_evaluation
from .route.evaluation import RouteEvaluation


def _legs_of(ev: RouteEvaluation, pre: RouteEvaluation | None,
             post: RouteEvaluation | None) -> list[RouteEvaluation]:
    return [e for e in (pre, ev, post) if e is not None]


def assemble_plan(ports, problems, results, baselines, sources, approaches, env, spec, method,
              objective, depart_s, rta_s, leg_rtas, gens, evals, compute_s,
              deadlines) -> RoutePlan:
    wps: list[Waypoint] = []
    flags = 0
    plan_parts, base_parts, spans, fixed = [], [], [], []
    for k, ev in enumerate(results):
        pre, post = approaches[k]
        parts = _legs_of(ev, pre, post)
        plan_parts.extend(parts)
        if baselines:
            base_parts.extend(_legs_of(baselines[k][2], pre, post))
        for j, part in enumerate(parts):
            m = part.legs["rpm"].shape[1]
            weather = env.weather(part.lon_deg[0, :m], part.lat_deg[0, :m], part.time_s[0, :m])
            names = {}
            if j == 0:
                names[0] = ports[k].name
            if j == len(parts) - 1:
                names[m] = ports[k + 1].name
            w = waypoints_from_evaluation(part, weather, names)
            start = max(len(wps) - 1, 0)
            if wps:  # the junction node carries the next part's leg values
                wps[-1] = dataclasses.replace(w[0], port=wps[-1].port or w[0].port)
                w = w[1:]
            wps.extend(w)
            if part is ev and sources[k] == "canal":
                fixed.append((start, len(wps) - 1))
            elif part is ev and sources[k] != "strait":
                spans.append((start, len(wps) - 1))
            if part is ev and sources[k] != "strait":  # approaches and strait passages are
                # computed against land, clearance and depth: their flags inform, not decide
                flags |= int(part.flags[0]) & ~2
        if float(parts[-1].eta_s[0]) > deadlines[k] and sources[k] not in ("strait", "canal"):
            flags |= 2  # inserted points carry no user RTA: a fixed passage's time is made
            # up on the optimised leg after it
    fuel = sum(float(ev.fuel_t[0]) for ev in plan_parts)
    dist = sum(float(ev.distance_m[0]) for ev in plan_parts) / M_PER_NM
    eta = float(plan_parts[-1].eta_s[0])
    b_fuel = sum(float(e.fuel_t[0]) for e in base_parts) if baselines else float("nan")
    b_dist = sum(float(e.distance_m[0]) for e in base_parts) / M_PER_NM if baselines else 0.0
    b_eta = float(base_parts[-1].eta_s[0]) if baselines else float("nan")
    b_ok = all(bool(b[2].feasible[0]) for b in baselines) if baselines else False
    b_track = tuple((float(la), float(lo)) for e in base_parts
                    for lo, la in zip(e.lon_deg[0], e.lat_deg[0], strict=True))
    b_method = "+".join(sorted({b[0] for b in baselines})) if baselines else ""
    said = baseline_words(baselines, b_method, b_ok)
    return RoutePlan(
        plan_id=uuid.uuid4().hex[:12], method=method, seed_source=sources[0],
        objective=objective, ship_name=getattr(spec, "name", ""), cycle_id=env.cycle_id,
        departure_s=depart_s, rta_s=rta_s, eta_s=eta, feasible=flags == 0,
        infeasible_reasons=reasons_of(flags), total_fuel_t=fuel, total_distance_nm=dist,
        total_time_s=eta - depart_s, baseline_fuel_t=b_fuel,
        baseline_method=b_method,
        baseline_distance_nm=b_dist, baseline_eta_s=b_eta, baseline_feasible=b_ok,
        baseline_rpm=float(baselines[0][1]) if baselines else float("nan"),
        compute_time_s=compute_s, waypoints=tuple(wps),
        ports=tuple(p.name for p in ports), stage_s=problems[0].stage_s, generations=gens,
        evaluations=evals,
        vessel_max_wave_m=float(problems[0].limits.max_hs_m or float("nan")),
        vessel_max_wind_m_s=float(problems[0].limits.max_wind_m_s or float("nan")),
        baseline_track=b_track, leg_rtas_s=tuple(leg_rtas), optimised_spans=tuple(spans),
        extra={"fixed_passages": tuple(fixed)} if fixed else {}, warnings=said,
    )


def baseline_words(baselines: list, method: str, feasible: bool) -> tuple[str, ...]:
    """The warning that the fuel comparison is against a baseline the ship could not sail
    (its constraint flags named), so a negative or large saving is read for what it is."""
    if feasible or not baselines:
        return ()
    flags = 0
    for b in baselines:
        flags |= int(b[2].flags[0])
    why = "; ".join(reasons_of(flags)) or "constraints"
    return (f"baseline ({method}, constant RPM) is "
            f"infeasible ({why}): the fuel saving is against a route the ship could not sail",)
