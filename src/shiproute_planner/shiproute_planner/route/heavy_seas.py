"""What a member stage above the ship's wave limit really costs: heave-to, then the fuel to
still meet the RTA.

Sailing an ensemble member, the route model counts a stage in seas above the ship's limit
as sailed at the planned RPM with the ISO 15016 added resistance only (none at all from
abaft the beam): in fuel such a member is cheap, the ship merely arrives late. A navigator
judges a plan by what it costs if that member comes true and the ship still meets its RTA.
Every plan evaluated on members (the risk-aware GA and every plan's ensemble statement) is
therefore counted with this model, stated in the plan (`HEAVY_SEAS_MODEL`):

1. **Heave-to above the limit.** A stage whose significant wave height (sampled at its start,
   as the route model samples it) exceeds the ship's limit (`seakeeping.max_hs_m`) is not
   sailed as planned: the master heaves to, bow to the sea at steerage way, the engine at its
   minimum steady RPM (`engine.rpm_min`, "dead slow"), the action for seas beyond what the
   ship keeps in the IMO guidance to masters for adverse weather (MSC.1/Circ.1228, 2007: reduce
   speed, alter course) and heavy-weather seamanship. Progress along the route while hove to
   is neglected (the ship holds the sea on her bow, not the route); the stage is sailed as
   planned once the sea allows. The voyage is delayed by the stage's duration and burns the
   calm-water fuel rate at `rpm_min` for it on top of the planned stage.
2. **RTA recovery by the propeller law.** A member that then arrives after the RTA (delay D
   beyond its slack) speeds up on what remains after its last heave-to (time T_r at planned
   speeds, the deferred stage included; without heave-to the whole voyage: its lateness comes
   from the member's weather all along): P ~ V^3, so the fuel for a given distance goes with
   V^2 and the remaining fuel F_r grows by (T_r / (T_r - D))^2. The speed factor is capped
   where the remaining legs' time-weighted mean engine load reaches MCR, (1 / load)^(1/3);
   beyond it the member arrives late by what is left, at MCR. The error of the propeller law
   against an exact re-solve with the ship model is bounded in the tests.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from ..ship.seastate import SeaState
from ..ship.spec import ShipSpec
from .evaluation import RouteEvaluation
from .problem import RouteProblem

HEAVY_SEAS_MODEL = (
    "member stages above the ship's Hs limit: hove to at steerage way (engine at its minimum "
    "RPM, no progress along the route) for the stage, then sailed as planned (IMO "
    "MSC.1/Circ.1228 heavy-weather guidance); a member then late recovers the delay on the "
    "rest of its voyage by the propeller law (remaining fuel x (T_r / (T_r - delay))^2, speed "
    "capped at MCR, late beyond that)")


@dataclass(frozen=True)
class HeaveTo:
    """What the ship does hove to: its engine's minimum RPM and the fuel rate at it."""

    rpm: float
    fuel_t_per_h: float


@dataclass(frozen=True)
class MemberVoyage:
    """Per row of a member evaluation: the voyage as sailed with heave-to and RTA recovery."""

    fuel_t: np.ndarray  # planned fuel + heave-to fuel + recovery fuel
    eta_s: np.ndarray  # the RTA when recovered; later when even MCR cannot make it
    heave_to_s: np.ndarray  # time hove to
    heave_to_fuel_t: np.ndarray
    recovery_fuel_t: np.ndarray  # extra fuel to make up the delay
    speed_factor: np.ndarray  # speed of the recovered part over the planned one (1: none)
    unrecoverable: np.ndarray  # bool: late even at MCR


@functools.lru_cache(maxsize=16)
def heave_to_of(ship: ShipSpec) -> HeaveTo:
    """The ship's heave-to: calm-water fuel rate at its minimum RPM (the fast ship model)."""
    from ..ship.fast import fast_model

    rpm = float(ship.engine.rpm_min)
    perf = fast_model(ship).evaluate(np.array([rpm]), np.array([0.0]), SeaState.calm(1))
    return HeaveTo(rpm, float(np.asarray(perf.fuel_t_per_h).ravel()[0]))


def recovery_factor(remaining_s: np.ndarray, delay_s: np.ndarray, mean_load: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray]:
    """(speed factor, delay left) to make up `delay_s` within `remaining_s` at planned speeds:
    T_r / (T_r - D), capped where the mean engine load `mean_load` (fraction of MCR) times
    the factor cubed reaches 1; no speed-up without delay."""
    t_r = np.maximum(np.asarray(remaining_s, dtype=float), 1e-9)
    d = np.maximum(np.asarray(delay_s, dtype=float), 0.0)
    cap = np.maximum(np.maximum(np.asarray(mean_load, dtype=float), 1e-6) ** (-1.0 / 3.0), 1.0)
    with np.errstate(divide="ignore"):
        need = np.where(d < t_r, t_r / np.maximum(t_r - d, 1e-9), np.inf)
    k = np.where(d > 0, np.minimum(need, cap), 1.0)
    left = np.maximum(d - t_r * (1.0 - 1.0 / k), 0.0)
    return k, np.where(need <= cap, 0.0, left)


def member_voyage(problem: RouteProblem, ev: RouteEvaluation, heave: HeaveTo) -> MemberVoyage:
    """Each row of `ev` (a route sailed on one member) with heave-to above the problem's Hs
    limit and the fuel to recover the delay (module docstring)."""
    legs = ev.legs
    dur = legs["duration_s"]
    rows, m = dur.shape
    limit = problem.limits.max_hs_m
    active = dur > 0
    if limit is None:
        exceed = np.zeros(dur.shape, dtype=bool)
    else:
        exceed = active & (np.nan_to_num(legs["hs_m"], nan=0.0) > limit)
    heave_s = np.where(exceed, dur, 0.0).sum(axis=1)
    heave_fuel = heave.fuel_t_per_h * heave_s / 3600.0
    hit = exceed.any(axis=1)
    last = np.where(hit, m - 1 - np.argmax(exceed[:, ::-1], axis=1), 0)
    after = np.arange(m)[None, :] >= last[:, None]
    start = ev.time_s[np.arange(rows), last]
    remaining_s = ev.eta_s - start
    remaining_fuel = np.where(after, legs["fuel_t"], 0.0).sum(axis=1)
    sailed = np.where(after & active, dur, 0.0)
    load = np.nan_to_num(legs["engine_load"], nan=1.0)
    mean_load = (load * sailed).sum(axis=1) / np.maximum(sailed.sum(axis=1), 1e-9)
    delay = ev.eta_s + heave_s - problem.rta_s
    k, left = recovery_factor(remaining_s, delay, mean_load)
    recovery = remaining_fuel * (k**2 - 1.0)
    eta = np.where(delay > 0, problem.rta_s + left, ev.eta_s + heave_s)
    return MemberVoyage(ev.fuel_t + heave_fuel + recovery, eta, heave_s, heave_fuel, recovery,
                        k, left > 0)
