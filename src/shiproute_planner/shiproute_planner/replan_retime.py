"""A re-plan's route re-sailed to arrive on time: the previous plan's remainder (and the
new search's result) keeps its waypoints but gets its RPMs scaled by one factor when it
arrives more than OFF_TARGET_S off its target (TARGET_BEFORE_RTA_S before the RTA), as a
navigator slows down a ship that would arrive hours early; a second sail corrects the factor
(speed is only about proportional to RPM, and the weather met changes with the times).

When slowing down breaks a constraint (the storm catches the ship), only the legs after the
last broken one are re-timed. The re-timed route replaces the route only when it is feasible
and not worse than before (fuel, constraints); either way the plan says what was done.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from shiproute_core.flags import FLAG_RTA

from .plan_prepare import PreparedVoyage
from .route.evaluation import RouteEvaluation
from .route.problem import RouteProblem
from .route.sail_fixed_point import sail_track
from .rpm_factor import TARGET_BEFORE_RTA_S, retimed_rpm

OFF_TARGET_S = 1800.0  # arrivals this close to the target are left as they are
SETTLED_S = 300.0  # a re-sail this close to the target needs no correction
MAX_SAILS = 3  # re-sails of one route (first factor, corrections, later legs only)
PART_WINDOW_S = 30 * 86400.0  # a part has no RTA of its own (the plan's is checked after)
FUEL_EPS = 1e-6  # relative: a re-timed route this close in fuel is not "worse"


@dataclass(frozen=True)
class Piece:
    """One part of a route as the plan sails it: its evaluation (one row) and whether its
    flags decide the plan's feasibility (an optimised span) or inform (approaches, strait
    passages: computed against land; their land is not re-tested here)."""

    evaluation: RouteEvaluation
    decides: bool

    def rpm(self) -> np.ndarray:
        """RPM per leg."""
        return np.asarray(self.evaluation.legs["rpm"][0], dtype=float)

    def duration_s(self) -> np.ndarray:
        """Duration per leg [s]."""
        return np.asarray(self.evaluation.legs["duration_s"][0], dtype=float)


def resail(prep: PreparedVoyage, piece: Piece, start_s: float, rpm: np.ndarray) -> Piece:
    """`piece` sailed again from `start_s` at `rpm` per leg on the same waypoints (the
    deciding parts with the land test, as an optimised span is judged)."""
    ev = piece.evaluation
    lon, lat = ev.lon_deg[0], ev.lat_deg[0]
    problem = RouteProblem(float(lon[0]), float(lat[0]), float(lon[-1]), float(lat[-1]),
                           start_s, start_s + PART_WINDOW_S, prep.limits)
    out = sail_track(problem, prep.env, prep.land if piece.decides else None, lon, lat, rpm,
                     time_guess_s=ev.time_s[0])
    return Piece(out, piece.decides)


@dataclass(frozen=True)
class Verdict:
    """What a sailed route comes to: deciding flags (0: feasible), on time, fuel [t]."""

    flags: int
    on_time: bool
    fuel_t: float
    arrival_s: float

    @property
    def feasible(self) -> bool:
        """Every deciding constraint holds and the route is on time."""
        return self.flags == 0 and self.on_time


def verdict(pieces: Sequence[Piece], prep: PreparedVoyage) -> Verdict:
    """The verdict on `pieces` as the plan's assembly judges them."""
    flags = 0
    for p in pieces:
        if p.decides:
            flags |= int(p.evaluation.flags[0]) & ~FLAG_RTA  # the plan's RTA: checked here
    arrival = float(pieces[-1].evaluation.eta_s[0])
    return Verdict(flags, arrival <= prep.rta_s + prep.rta_tolerance_s,
                   sum(float(p.evaluation.fuel_t[0]) for p in pieces), arrival)


def last_broken_leg(pieces: Sequence[Piece]) -> int | None:
    """Index (over all legs in sailing order) of the last leg of a deciding piece with a
    constraint broken, None when none is."""
    last, offset = None, 0
    for p in pieces:
        bad = np.flatnonzero(p.evaluation.leg_flags[0] != 0) if p.decides else np.empty(0)
        if bad.size:
            last = offset + int(bad.max())
        offset += p.rpm().size
    return last


def sail_all(prep: PreparedVoyage, pieces: Sequence[Piece], start_s: float,
             rpm: np.ndarray) -> list[Piece]:
    """`pieces` sailed in order from `start_s` at `rpm` (all legs in sailing order); a piece
    whose RPMs and start are unchanged is kept as it was."""
    out, t, i = [], start_s, 0
    for p in pieces:
        r = rpm[i:i + p.rpm().size]
        i += r.size
        same = (np.array_equal(r, p.rpm())
                and abs(float(p.evaluation.time_s[0, 0]) - t) <= 1e-6)
        q = p if same else resail(prep, p, t, r)
        out.append(q)
        t = float(q.evaluation.eta_s[0])
    return out


def within_engine(rpm: np.ndarray, base: np.ndarray, prep: PreparedVoyage) -> np.ndarray:
    """`rpm` with its legs' factors over `base` kept to one factor per stretch that the
    engine range allows (a factor is clipped, not each leg: the schedule's shape stays)."""
    lim = prep.limits
    changed = ~np.isclose(rpm, base)
    if not changed.any():
        return rpm
    f = float(np.median(rpm[changed] / base[changed]))
    lo = lim.rpm_min / float(base[changed].min())
    hi = lim.rpm_max / float(base[changed].max())
    out = base.copy()
    out[changed] = base[changed] * float(np.clip(f, lo, hi))
    return out


@dataclass(frozen=True)
class Retimed:
    """The route's pieces (re-timed or not) and what the plan says about it ("" nothing)."""

    pieces: tuple[Piece, ...]
    said: str
    retimed: bool


def retimed_route(prep: PreparedVoyage, pieces: Sequence[Piece], start_s: float,
                  what: str) -> Retimed:
    """`pieces` (sailed from `start_s`) re-timed to arrive TARGET_BEFORE_RTA_S before the
    RTA when they arrive more than OFF_TARGET_S off it, kept only when feasible and not
    worse; `what` names the route in the plan's words."""
    pieces = tuple(pieces)
    target_s = prep.rta_s - TARGET_BEFORE_RTA_S
    before = verdict(pieces, prep)
    off_s = before.arrival_s - target_s
    if abs(off_s) <= OFF_TARGET_S:
        return Retimed(pieces, "", False)
    base = np.concatenate([p.rpm() for p in pieces])
    window_s = target_s - start_s
    current, cut, changed = list(pieces), 0, False
    for _ in range(MAX_SAILS):
        durations = np.concatenate([p.duration_s() for p in current])
        rpm_now = np.concatenate([p.rpm() for p in current])
        rpm = retimed_rpm(rpm_now, durations, cut, window_s)
        if rpm is None:
            break
        rpm = within_engine(rpm, base, prep)
        sailed = sail_all(prep, current, start_s, rpm)
        now = verdict(sailed, prep)
        broken = last_broken_leg(sailed)
        if now.flags and not before.flags and broken is not None and cut == 0:
            # re-timing from the start met weather the route avoided: keep the route's own
            # times up to and through the last broken leg, re-time only the legs after it
            cut = broken + 1
            current = list(pieces)
            continue
        current, changed = sailed, True
        if abs(now.arrival_s - target_s) <= SETTLED_S:
            break
    after = verdict(current, prep)
    better = after.feasible and (not before.feasible
                                 or after.fuel_t <= before.fuel_t * (1.0 + FUEL_EPS))
    if better and changed:
        from_leg = "" if cut == 0 else f" from leg {cut + 1} on"
        said = (f"re-timed: {what} arrived {off_target_words(off_s)} against its target (RTA - "
                f"{TARGET_BEFORE_RTA_S / 3600.0:g} h); re-sailed at one RPM factor{from_leg}, "
                f"now {(after.arrival_s - target_s) / 3600.0:+.1f} h, fuel "
                f"{before.fuel_t:.1f} -> {after.fuel_t:.1f} t")
        return Retimed(tuple(current), said, True)
    why = ("no time is left to re-time its legs" if not changed
           else "the re-timed route broke a constraint" if not after.feasible
           else "the re-timed route cost more fuel")
    return Retimed(pieces, not_retimed_words(what, off_s, why), False)


def off_target_words(off_s: float) -> str:
    """An arrival `off_s` [s] from its target in words ("2.5 h early", "1.0 h late")."""
    return f"{-off_s / 3600.0:.1f} h early" if off_s < 0 else f"{off_s / 3600.0:.1f} h late"


def not_retimed_words(what: str, off_s: float, why: str) -> str:
    """The plan's words for a route left as it was."""
    return (f"not re-timed: {what} arrives {off_target_words(off_s)} against its target "
            f"(RTA - {TARGET_BEFORE_RTA_S / 3600.0:g} h); {why}")


Leg = RouteEvaluation | None


@dataclass(frozen=True)
class RetimedLegs:
    """A voyage's legs after `retimed_legs`: per leg its main result, (pre, post) approaches
    and arrival; the plan's words ("" nothing to say) and whether anything changed."""

    results: tuple[RouteEvaluation, ...]
    approaches: tuple[tuple[Leg, Leg], ...]
    arrivals: tuple[float, ...]
    said: str
    retimed: bool


def not_retimable(prep: PreparedVoyage) -> str:
    """Why a voyage's legs are not re-timed at one factor ("": they are)."""
    if prep.canal_legs:
        return "a canal transit lies ahead (its speed is the canal's)"
    if prep.call_at:
        return "port calls lie ahead (their windows are scheduled per leg)"
    if prep.rta_warning:
        return "the RTA is beyond reach"
    if prep.risk is not None:
        return "an ensemble plan (the members' spread is not re-sailed)"
    return ""


def retimed_legs(prep: PreparedVoyage, results: Sequence[RouteEvaluation],
                 sources: Sequence[str], approaches: Sequence[tuple[Leg, Leg]],
                 start_s: float, what: str) -> RetimedLegs:
    """The legs (main result of each, its approaches) as `retimed_route` leaves them; an
    optimised span's flags decide, those of approaches and strait passages inform."""
    layout: list[tuple[int, int]] = []  # (leg, 0 pre | 1 main | 2 post) of each piece
    pieces: list[Piece] = []
    for k, (ev, (pre, post)) in enumerate(zip(results, approaches, strict=True)):
        for j, part in enumerate((pre, ev, post)):
            if part is not None:
                layout.append((k, j))
                pieces.append(Piece(part, j == 1 and sources[k] not in ("strait", "canal")))
    arrivals = tuple(float(post.eta_s[0]) if post is not None else float(ev.eta_s[0])
                     for ev, (_, post) in zip(results, approaches, strict=True))
    unchanged = RetimedLegs(tuple(results), tuple(approaches), arrivals, "", False)
    off_s = arrivals[-1] - (prep.rta_s - TARGET_BEFORE_RTA_S)
    if abs(off_s) <= OFF_TARGET_S:
        return unchanged
    why = not_retimable(prep)
    if why:
        return RetimedLegs(tuple(results), tuple(approaches), arrivals,
                           not_retimed_words(what, off_s, why), False)
    out = retimed_route(prep, pieces, start_s, what)
    if not out.retimed:
        return RetimedLegs(tuple(results), tuple(approaches), arrivals, out.said, False)
    mains = list(results)
    outer = [list(a) for a in approaches]
    for (k, j), piece in zip(layout, out.pieces, strict=True):
        if j == 1:
            mains[k] = piece.evaluation
        else:
            outer[k][j // 2] = piece.evaluation
    ends = tuple(float((o[1] or ev).eta_s[0]) for ev, o in zip(mains, outer, strict=True))
    return RetimedLegs(tuple(mains), tuple((o[0], o[1]) for o in outer), ends, out.said,
                       True)
