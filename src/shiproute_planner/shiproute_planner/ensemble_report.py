"""What a plan made on an ensemble states: its spread over the members.

The plan's genes of every optimised leg are sailed on each member (the compiled member
evaluation, `route.member_eval`; a leg sailed as a track, a constant-RPM baseline chosen over
the search, by the exact evaluator on each member's forecast); per member the voyage's fuel
and ETA are the plan's own plus the member's difference on those legs (port approaches,
straits and canals as planned).
Stated: P10/P50/P90 of fuel and ETA (the smallest member value whose cumulative weight
reaches the level), the probability (member weight) of each constraint being violated, per
leg the members' min/median/max of Hs and wind speed, which risk measure chose the plan and
how many members it saw. Every member is sailed with heave-to above the ship's wave limit
and the fuel to still meet the RTA (`route.heavy_seas`), stated in the `heavy_seas` block and
a warning: fuel quantiles include it, lateness is what even MCR cannot make up.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

import numpy as np
from shiproute_core.flags import FLAG_NAMES, FLAG_RTA, FLAG_WAVE_LIMIT

from .geo.landmask import LandMask
from .plan_types import RoutePlan
from .route.encoding import join_genes
from .route.environment import Environment
from .route.evaluation import RouteEvaluation
from .route.fast_eval import fast_evaluator
from .route.heavy_seas import HEAVY_SEAS_MODEL
from .route.member_eval import CHANCE_TOLERANCE, SEA_KEEPING, member_outcomes
from .route.problem import RouteProblem
from .route.risk import RiskSpec, weighted_quantile
from .route.sail import sail_tracks

QUANTILES = (0.1, 0.5, 0.9)


@dataclass(frozen=True)
class MemberLeg:
    """One optimised leg of a plan: its problem, chosen genes and exact (member-mean) result."""

    problem: RouteProblem
    genes: np.ndarray | None
    exact: RouteEvaluation


def _genes_of(leg: MemberLeg) -> np.ndarray | None:
    """Stage genes (headings, RPMs) of a leg's exact result when it sails the problem's
    stages (a constant-RPM baseline chosen over the GA does), else None."""
    n = leg.problem.n_stages
    legs = leg.exact.legs
    if legs["rpm"].shape[1] != n + 1:
        return None
    return join_genes(legs["heading_deg"][:1, :n], legs["rpm"][:1])[0]


def _track_on_members(leg: MemberLeg, env: Environment, land: LandMask | None,
                      members: Any) -> RouteEvaluation:
    """A leg sailed as a track (a constant-RPM baseline chosen over the search: its nodes
    are not stage genes) on each member's own forecast by the exact evaluator, at the RPMs it
    was planned with; rows member-major like `FastEvaluator.evaluate_members`."""
    from shiproute_weather.sampling.sampler import ForecastSampler

    sampler = env.sampler
    assert isinstance(sampler, ForecastSampler), "members come with a ForecastSampler"
    lon, lat, rpm = leg.exact.lon_deg[:1], leg.exact.lat_deg[:1], leg.exact.legs["rpm"][0]
    rows = []
    for k in range(members.count):  # the members share the sampler's times and grid
        one = ForecastSampler.from_packed(members.data[k], sampler.times_s, sampler.grid,
                                          list(sampler.variables))
        rows.append(sail_tracks(leg.problem, dataclasses.replace(env, sampler=one, risk=None),
                                land, lon, lat, rpm))

    def stacked(name: str) -> np.ndarray:
        return np.concatenate([getattr(r, name) for r in rows])

    return RouteEvaluation(
        stacked("lon_deg"), stacked("lat_deg"), stacked("time_s"),
        {key: np.concatenate([r.legs[key] for r in rows]) for key in rows[0].legs},
        stacked("leg_flags"), stacked("fuel_t"), stacked("distance_m"), stacked("eta_s"),
        stacked("flags"), stacked("violation"), stacked("objective"))


def ensemble_members(env: Environment) -> Any:
    """The sampler's `MemberFields`, or None for a one-forecast environment."""
    return getattr(env.sampler, "members", None) if env.sampler is not None else None


def _quantiles(values: np.ndarray, w: np.ndarray) -> list[float]:
    return [float(weighted_quantile(values[:, None], w, q)[0]) for q in QUANTILES]


def _spread(values: np.ndarray, w: np.ndarray) -> dict[str, list[float]]:
    """Per leg (columns) the members' min, weighted median and max."""
    ok = np.all(np.isfinite(values), axis=0)
    med = np.full(values.shape[1], np.nan)
    if ok.any():
        med[ok] = weighted_quantile(values[:, ok], w, 0.5)
    lo = np.where(ok, np.min(values, axis=0), np.nan)
    hi = np.where(ok, np.max(values, axis=0), np.nan)
    return {"min": lo.tolist(), "median": med.tolist(), "max": hi.tolist()}


def ensemble_block(plan: RoutePlan, env: Environment, land: LandMask | None,
                   legs: list[MemberLeg], risk: RiskSpec | None,
                   rta_tolerance_s: float) -> tuple[dict[str, Any] | None, list[str]]:
    """(the plan JSON's `ensemble` block, warning sentences); (None, []) without members."""
    members = ensemble_members(env)
    if members is None:
        return None, ([f"risk measure {risk.label} asked for, but the forecast has one member: "
                       "planned on it"] if risk is not None else [])
    w = members.weights
    m_count = members.count
    n_wp = len(plan.waypoints)
    fuel = np.full(m_count, plan.total_fuel_t)
    eta = np.full(m_count, plan.eta_s)
    flags = np.zeros(m_count, dtype=np.uint32)
    hs = np.full((m_count, max(n_wp - 1, 0)), np.nan)
    wind = hs.copy()
    heave_s, recovery_t = np.zeros(m_count), np.zeros(m_count)
    unrecoverable = np.zeros(m_count, dtype=bool)
    spans = plan.optimised_spans or ((0, n_wp - 1),)
    for leg, (a, b) in zip(legs, spans, strict=False):
        fast = fast_evaluator(leg.problem, env, land)
        if fast is None:
            return None, ["ensemble spread not evaluated: the ship model has no compiled "
                          "kernel; the plan was made on the members' mean forecast"]
        genes = leg.genes if leg.genes is not None else _genes_of(leg)
        ev = (fast.evaluate_members(genes[None, :]) if genes is not None
              else _track_on_members(leg, env, land, members))
        out = member_outcomes(leg.problem, ev, m_count, w, fast)
        if out.voyage is not None:
            heave_s += out.voyage.heave_to_s
            recovery_t += out.voyage.heave_to_fuel_t + out.voyage.recovery_fuel_t
            unrecoverable |= out.voyage.unrecoverable
        fuel += out.fuel_t[:, 0] - float(leg.exact.fuel_t[0])
        eta += out.eta_s[:, 0] - float(leg.exact.eta_s[0])
        flags |= ev.flags & ~np.uint32(FLAG_RTA)
        if b - a == ev.legs["hs_m"].shape[1]:
            hs[:, a:b] = ev.legs["hs_m"]
            wind[:, a:b] = ev.legs["wind_speed_m_s"]
    late = eta > plan.rta_s + rta_tolerance_s
    flags |= np.where(late, FLAG_RTA, 0).astype(np.uint32)
    p_violated = {text: float(w @ ((flags & bit) != 0)) for bit, text in FLAG_NAMES.items()
                  if np.any(flags & bit)}
    block = {
        "members": m_count, "kind": members.kind, "labels": list(members.labels),
        "weights": w.tolist(),
        "risk_measure": risk.label if risk is not None else "none (planned on the members' mean)",
        "p_hs_max": risk.p_hs_max if risk is not None else None,
        "p_late_max": risk.p_late_max if risk is not None else None,
        "fuel_t": dict(zip(("p10", "p50", "p90"), _quantiles(fuel, w), strict=True),
                       mean=float(w @ fuel), per_member=fuel.tolist()),
        "eta_s": dict(zip(("p10", "p50", "p90"), _quantiles(eta, w), strict=True),
                      per_member=eta.tolist()),
        "p_hs_violation": float(w @ ((flags & FLAG_WAVE_LIMIT) != 0)),
        "p_late": float(w @ late),
        "p_sea_keeping_violation": float(w @ ((flags & SEA_KEEPING) != 0)),
        "p_any_violation": float(w @ (flags != 0)),
        "p_violated": p_violated,
        "legs": {"hs_m": _spread(hs, w), "wind_speed_m_s": _spread(wind, w)},
        "heavy_seas": {"model": HEAVY_SEAS_MODEL, "p_heave_to": float(w @ (heave_s > 0)),
                       "heave_to_h": (heave_s / 3600.0).tolist(),
                       "added_fuel_t": recovery_t.tolist(),
                       "p_rta_unrecoverable": float(w @ unrecoverable)},
    }
    how = ("planned on the members' mean forecast (no risk measure asked)" if risk is None
           else f"planned on risk measure {risk.label} with P(Hs > limit) <= "
           f"{risk.p_hs_max:g} (the other sea-keeping limits likewise) and P(late) <= "
           f"{risk.p_late_max:g}")
    said = [f"ensemble of {m_count} members ({members.kind}): " + how
            + f"; fuel P10/P50/P90 {block['fuel_t']['p10']:.1f}/{block['fuel_t']['p50']:.1f}/"
            f"{block['fuel_t']['p90']:.1f} t, P(Hs > limit) {block['p_hs_violation']:.2f}, "
            f"P(late) {block['p_late']:.2f}", heavy_seas_sentence(block["heavy_seas"], w)]
    return block, said + unmet_chance_constraints(block, risk)


def heavy_seas_sentence(heavy: dict[str, Any], w: np.ndarray) -> str:
    """The plan's sentence on how its members were sailed in seas above the limit."""
    hours = np.asarray(heavy["heave_to_h"])
    added = np.asarray(heavy["added_fuel_t"])
    hit = hours > 0
    worst = (f"; where it does, hove to up to {hours.max():.0f} h and up to "
             f"{added.max():.1f} t added" if hit.any() else "")
    return (f"members sailed with heavy-seas physics ({heavy['model']}): P(heave-to) "
            f"{heavy['p_heave_to']:.2f}{worst}; mean fuel added by heave-to and RTA recovery "
            f"{float(w @ added):.1f} t; P(RTA not recoverable even at MCR) "
            f"{heavy['p_rta_unrecoverable']:.2f}")


def unmet_chance_constraints(block: dict[str, Any], risk: RiskSpec | None) -> list[str]:
    """A sentence per chance constraint the plan misses over the members: which, achieved
    against asked (a best-effort plan must say it is one)."""
    if risk is None:
        return []
    out = []
    for name, achieved, asked in (
            ("P(Hs > limit)", block["p_hs_violation"], risk.p_hs_max),
            ("P(another sea-keeping limit exceeded)", block["p_sea_keeping_violation"],
             risk.p_hs_max),
            ("P(late)", block["p_late"], risk.p_late_max)):
        if achieved > asked + CHANCE_TOLERANCE:
            out.append(f"chance constraint {name} <= {asked:g} not met: {achieved:.2f} of the "
                       f"members' weight (best effort under {risk.label}: the search found "
                       "no route that meets it)")
    return out


def with_ensemble(plan: RoutePlan, block: dict[str, Any] | None, said: list[str]) -> RoutePlan:
    """The plan with its ensemble statement in `extra` and its warnings."""
    if block is None and not said:
        return plan
    if block is None:
        return dataclasses.replace(plan, warnings=(*plan.warnings, *said))
    legs = block["legs"]

    def spread(name: str) -> tuple[tuple[float, float, float], ...]:
        return tuple(zip(legs[name]["min"], legs[name]["median"], legs[name]["max"],
                         strict=True))

    f, e = block["fuel_t"], block["eta_s"]
    return dataclasses.replace(
        plan, warnings=(*plan.warnings, *said), extra={**plan.extra, "ensemble": block},
        ensemble_members=int(block["members"]),
        risk_measure="" if block["p_hs_max"] is None else str(block["risk_measure"]),
        fuel_quantiles_t=(f["p10"], f["p50"], f["p90"]),
        eta_quantiles_s=(e["p10"], e["p50"], e["p90"]),
        p_hs_violation=float(block["p_hs_violation"]), p_late=float(block["p_late"]),
        leg_hs_spread_m=spread("hs_m"), leg_wind_spread_m_s=spread("wind_speed_m_s"))


def summary_lines(block: dict[str, Any]) -> list[str]:
    """The CLI summary's lines of an `ensemble` block."""
    from datetime import UTC, datetime

    def iso(t: float) -> str:
        return datetime.fromtimestamp(t, UTC).strftime("%m-%d %H:%MZ")

    f, e = block["fuel_t"], block["eta_s"]
    hs = block["legs"]["hs_m"]
    worst_leg = np.nanargmax(np.asarray(hs["max"], dtype=float)) if np.any(
        np.isfinite(np.asarray(hs["max"], dtype=float))) else None
    lines = [
        f"ensemble   {block['members']} members ({block['kind']}), risk measure "
        f"{block['risk_measure']}",
        f"  fuel     P10/P50/P90 {f['p10']:.1f} / {f['p50']:.1f} / {f['p90']:.1f} t "
        f"(mean {f['mean']:.1f} t)",
        f"  ETA      P10/P50/P90 {iso(e['p10'])} / {iso(e['p50'])} / {iso(e['p90'])}",
        f"  P(viol.) Hs > limit {block['p_hs_violation']:.2f}, late {block['p_late']:.2f}, "
        f"any constraint {block['p_any_violation']:.2f}",
    ]
    heavy = block.get("heavy_seas")
    if heavy is not None:
        added = np.asarray(heavy["added_fuel_t"], dtype=float)
        lines.append(f"  heavy seas P(heave-to) {heavy['p_heave_to']:.2f}, fuel added to meet "
                     f"the RTA mean {float(np.asarray(block['weights']) @ added):.1f} t, "
                     f"P(RTA not recoverable) {heavy['p_rta_unrecoverable']:.2f}")
    if worst_leg is not None:
        k = int(worst_leg)
        w = block["legs"]["wind_speed_m_s"]
        lines.append(f"  roughest leg {k}: Hs {hs['min'][k]:.1f} / {hs['median'][k]:.1f} / "
                     f"{hs['max'][k]:.1f} m, wind {w['min'][k]:.1f} / {w['median'][k]:.1f} / "
                     f"{w['max'][k]:.1f} m/s (member min / median / max)")
    return lines
