"""Busy straits as computed passages: where a voyage's sea lane runs through a strait, the
strait becomes a leg of its own between two gates in open water on either side, computed on
the fine navigable-water grid (`route.passages`: full-resolution land, the strait's own
clearance, depth) and sailed at the speed of the leg before it; the optimiser plans the open
sea between the gates.

Each strait keeps the largest clearance from land it has room for, starting from its own
(0.5 NM in the wide ones; the Bosphorus is ~0.4 NM wide at Rumeli Hisari, the Dardanelles
~0.65 NM at Canakkale, so they start lower and may go down to 0.1 NM). Gates lie ~15-40 NM
outside the narrows on the sea lane (positions checked to be open water at GSHHG full
resolution).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from shiproute_core.geodesy import M_PER_NM, densify_track, inverse, unwrap_near

from .route.nearest import nearest_node

NEAR_M = 25_000.0  # a lane "uses" a strait when it passes both gates this close


@dataclass(frozen=True)
class Strait:
    """A strait: its two gates (lat, lon), the clearances [NM] tried, largest first, and,
    for a strait with a draft limit, the strait a deeper ship takes instead."""

    name: str
    gates: tuple[tuple[float, float], tuple[float, float]]
    clearances_nm: tuple[float, ...] = (0.5, 0.25, 0.1, 0.0)
    max_draft_m: float = float("inf")
    round_via: str = ""  # name of the strait of this table a deeper ship takes
    # (lat, lon) guide from the first gate to the second for a strait taken as a way round
    # (no sea lane leads through it): the passage is computed in a corridor round it
    guide: tuple[tuple[float, float], ...] = ()


STRAITS: tuple[Strait, ...] = (
    Strait("Strait of Dover", ((50.70, 1.00), (51.15, 2.05))),
    Strait("Strait of Gibraltar", ((35.90, -6.20), (36.05, -4.95))),
    Strait("Singapore Strait", ((1.20, 103.55), (1.40, 104.55))),
    Strait("Strait of Hormuz", ((26.25, 55.95), (25.95, 57.05))),
    Strait("Bab-el-Mandeb", ((13.20, 42.90), (12.30, 43.75))),
    Strait("Dardanelles", ((39.95, 26.00), (40.45, 26.75)), (0.25, 0.1, 0.0)),
    Strait("Bosphorus", ((40.95, 28.98), (41.30, 29.15)), (0.1, 0.0)),
    Strait("Tsugaru Strait", ((41.45, 139.95), (41.55, 141.65))),
    Strait("Torres Strait", ((-10.40, 141.55), (-10.50, 142.85))),
    Strait("Sape Strait", ((-9.05, 119.60), (-8.05, 119.40))),
    # ~330 NM between the Pacific entrance off Cabo Pilar and the Atlantic one off Cabo
    # Virgenes; the First and Second Narrows (~2 NM and ~3.5 NM wide) open into bays
    # 15-20 NM wide, which the room raster reads as open water
    Strait("Strait of Magellan", ((-52.60, -75.05), (-52.40, -68.00))),
    # the Sound's Drogden channel is dredged to 8 m (Danish Maritime Authority: max draft
    # 7.7 m); deeper ships take the Great Belt's Route T (max draft 15 m)
    Strait("The Sound (Drogden)", ((56.40, 12.37), (55.28, 12.85)), max_draft_m=7.7,
           round_via="Great Belt (Route T)"),
    # Route T is the Danish transit route from the Skaw to north-east of Gedser (min depth
    # 17 m): it enters the Kattegat north of Laeso and keeps to the deep water east of Laeso
    # and Anholt (40-50 m in ETOPO5) before turning south-west for the Great Belt; the banks
    # south and west of Laeso and west of Anholt (3-14 m over 15-25 NM, real shoals, not
    # coastal smear) are why it exists, so its passage starts before them
    Strait("Great Belt (Route T)", ((57.60, 11.35), (54.45, 12.25)),
           guide=((57.60, 11.35), (57.25, 11.48), (56.95, 11.70), (56.70, 11.98),
                  (56.45, 11.90), (56.25, 11.45), (56.12, 10.98), (55.65, 10.82),
                  (55.45, 11.00), (55.20, 11.00),
                  (54.85, 10.97), (54.60, 11.20), (54.50, 11.70), (54.45, 12.25))),
)
STRAIT_BY_NAME = {s.name: s for s in STRAITS}


GATE_NAMES = frozenset(f"{s.name} gate" for s in STRAITS)


def is_gate(port) -> bool:
    """True for a gate inserted by `route_straits` or `shoal_passages.route_shoals` (open
    water: no approach)."""
    return port.locode == "" and is_gate_name(port.name)


def is_gate_name(name: str) -> bool:
    """True for the name `route_straits` or `shoal_passages.route_shoals` gives a gate."""
    return name in GATE_NAMES or name.startswith("deep-water passage past")


def straits_on_lane(lon_deg: np.ndarray, lat_deg: np.ndarray
                    ) -> list[tuple[int, Strait, bool, int, int]]:
    """Straits a sea-lane polyline passes: (index of the first gate met on the densified
    lane, strait, reversed, index of the first gate, index of the second) in lane order."""
    lon, lat = densify_track(np.unwrap(np.asarray(lon_deg, dtype=float), period=360.0),
                             np.asarray(lat_deg, dtype=float), 2000.0)
    lon, lat = np.asarray(lon, dtype=float), np.asarray(lat, dtype=float)
    found = []
    for s in STRAITS:
        idx = []
        for g_lat, g_lon in s.gates:
            near = nearest_node(lon, lat, g_lon, g_lat, NEAR_M)
            if near is None:
                break
            idx.append(near[0])
        if len(idx) == 2 and idx[0] != idx[1]:
            found.append((min(idx), s, idx[0] > idx[1], idx[0], idx[1]))
    return sorted(found, key=lambda f: f[0])


def _port_in_strait(strait: Strait, port) -> bool:
    """True when a port lies nearer either gate than the gates lie to each other (inside
    the strait or at its mouth: Singapore in the Singapore Strait)."""
    (la0, lo0), (la1, lo1) = strait.gates
    _, span = inverse(lo0, la0, lo1, la1)
    _, d = inverse(np.array([port.lon_deg, port.lon_deg]), np.array([port.lat_deg] * 2),
                   np.array([lo0, lo1]), np.array([la0, la1]))
    return bool(np.min(d) < float(span))


def _way_round(strait: Strait, rev: bool, draft_m: float
               ) -> tuple[Strait, np.ndarray, np.ndarray, list[str]] | None:
    """The strait a ship too deep for `strait` takes instead, with its guide in sailing
    order, and the plan's words; None when the ship fits."""
    if draft_m <= strait.max_draft_m or strait.round_via not in STRAIT_BY_NAME:
        return None
    other = STRAIT_BY_NAME[strait.round_via]
    guide = other.guide[::-1] if rev else other.guide
    note = (f"{strait.name}: the ship's draft {draft_m:.1f} m is over its limit "
            f"{strait.max_draft_m:g} m; routed through the {other.name} instead")
    return (other, np.array([g[1] for g in guide], dtype=float),
            np.array([g[0] for g in guide], dtype=float), [note])


def route_straits(ports: list, canal_legs: dict, via_rta: list, draft_m: float = 0.0
                  ) -> tuple[list, dict, dict, list, list[str]]:
    """Ports with strait gates inserted where the sea lane of a (non-canal) leg runs through
    a strait; returns (ports, canal legs re-indexed, {leg index: (strait, lane part gate to
    gate (lon, lat))}, via RTAs aligned to the new ports, notes for the plan). A strait with
    one of the leg's ports inside it is left to that port's approach passage; a strait whose
    draft limit the ship (`draft_m`) exceeds is replaced by its way round."""
    from .geo.ports import Port
    from .geo.sea_lanes import sea_lane_between

    rtas = list(via_rta) + [None] * (len(ports) - 2 - len(via_rta))
    out, out_rta, canals, straits, notes = [ports[0]], [], {}, {}, []
    for k in range(len(ports) - 1):
        a, b = ports[k], ports[k + 1]
        found = []
        if k in canal_legs:
            canals[len(out) - 1] = canal_legs[k]
        else:
            coords = sea_lane_between(a.lon_deg, a.lat_deg, b.lon_deg, b.lat_deg)
            if coords is not None and len(coords) > 1:
                found = straits_on_lane(coords[:, 0], coords[:, 1])
                lane = densify_track(np.unwrap(coords[:, 0], period=360.0), coords[:, 1],
                                     2000.0)
        for _, strait, rev, i0, i1 in found:
            g0, g1 = strait.gates[::-1] if rev else strait.gates
            if _port_in_strait(strait, a) or _port_in_strait(strait, b):
                continue  # the port's own approach passage covers it
            round_ = _way_round(strait, rev, draft_m)
            if round_ is not None:
                strait, part_lon, part_lat, said = round_
                notes += said
                g0, g1 = (part_lat[0], part_lon[0]), (part_lat[-1], part_lon[-1])
            else:
                lo, hi = sorted((i0, i1))
                part_lon = np.asarray(lane[0][lo:hi + 1], dtype=float)
                part_lat = np.asarray(lane[1][lo:hi + 1], dtype=float)
                part_lon = np.concatenate([[unwrap_near(g0[1], part_lon[0])], part_lon,
                                           [unwrap_near(g1[1], part_lon[-1])]])
                part_lat = np.concatenate([[g0[0]], part_lat, [g1[0]]])
            straits[len(out)] = (strait, part_lon, part_lat)
            out.append(Port(f"{strait.name} gate", "", g0[0], g0[1]))
            out.append(Port(f"{strait.name} gate", "", g1[0], g1[1]))
            out_rta += [None, None]
        out.append(b)
        if k < len(ports) - 2:
            out_rta.append(rtas[k])
    return out, canals, straits, out_rta, notes


def sail_strait(env, leg: tuple, depart_s: float, limits, stage_s: float,
                sea_rpm: float | None) -> tuple:
    """Compute a strait's passage between its gates and sail it at `sea_rpm` (mid-range RPM
    without one): (evaluation, RPM, problem, notes for the plan)."""
    import dataclasses

    from shiproute_planner.route.approach import Approach, sail_approach

    from .coastal_passages import cached_passage, passage_rules
    from .errors import PlannerError
    from .route.problem import RouteProblem

    strait, lane_lon, lane_lat = leg
    rpm = sea_rpm if sea_rpm is not None else 0.5 * (limits.rpm_min + limits.rpm_max)
    rpm = float(np.clip(rpm, limits.rpm_min, limits.rpm_max))
    rules = dataclasses.replace(passage_rules(limits.under_keel),
                                clearances_nm=strait.clearances_nm, berth_nm=0.0,
                                pilotage_nm=0.0)
    if rules.required_depth_m is not None:  # the squat of the speed it is sailed at,
        # rounded up to whole metres: the computed passage is cached by its rules, and a
        # plan on a new forecast sails the strait at a slightly other RPM
        rules = dataclasses.replace(rules, required_depth_m=max(
            rules.required_depth_m, math.ceil(_depth_needed_at(env, limits.under_keel, rpm))))
    notes = []
    try:
        p = cached_passage(lane_lon, lane_lat, rules)
    except (OSError, ValueError, MemoryError, PlannerError) as exc:  # the lane, said aloud
        p, why = None, f"not computed ({exc})"
    else:
        why = "no way through navigable water found"
    if p is None:
        lon, lat = lane_lon, lane_lat
        notes.append(f"{strait.name}: {why}; the sea lane's own geometry is sailed")
    else:
        lon, lat = p.lon_deg, p.lat_deg
        notes.append(f"{strait.name}: passage computed on the navigable-water grid, "
                     f"{strait_length_nm(lon, lat):.0f} NM, keeps >= {p.clearance_nm:g} NM "
                     "from land" + ("" if p.depth_limited or rules.required_depth_m is None
                                    else "; depth not limiting (no deep-enough way found)"))
    ev = sail_approach(env, Approach(np.asarray(lon, dtype=float),
                                     np.asarray(lat, dtype=float)), rpm, depart_s, limits)
    problem = RouteProblem(float(lon[0]), float(lat[0]), float(lon[-1]), float(lat[-1]),
                           depart_s, depart_s + 30 * 86400.0, limits, stage_s=stage_s,
                           dep_name=f"{strait.name} gate", arr_name=f"{strait.name} gate")
    return ev, rpm, problem, notes


def _depth_needed_at(env, under_keel, rpm: float) -> float:
    """Water depth [m] the ship needs at `rpm` in calm water (draft, squat, margin); the
    passage's depth limit at the 12-kn default when the model cannot say."""
    from .ship import SeaState

    try:
        perf = env.model.evaluate(np.array([rpm]), np.zeros(1), SeaState.calm((1,)))
        stw = np.asarray(perf.stw_m_s, dtype=float)
    except (ValueError, ArithmeticError, AttributeError, TypeError):
        return 0.0
    need = under_keel.required_depth_m(stw, np.zeros(1))
    return float(need[0]) if np.isfinite(need[0]) else 0.0


def strait_length_nm(lon: np.ndarray, lat: np.ndarray) -> float:
    """Geodesic length [NM] of a polyline."""
    return float(np.sum(inverse(lon[:-1], lat[:-1], lon[1:], lat[1:])[1])) / M_PER_NM
