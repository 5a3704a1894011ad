"""One voyage to plan from the text a user gives (CLI arguments, a fleet CSV/YAML row), turned
into the planner's `VoyageRequest` and `PlanOptions` and run through `planning.plan`:
`shiproute plan` and `shiproute fleet` build and run their plans here, so the same words mean
the same plan in both."""

from __future__ import annotations

import dataclasses
import math
import re
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .checks.parameters import require_number
from .errors import InvalidVoyageError
from .objectives import PLAN_OBJECTIVES as OBJECTIVES
from .objectives import Economics
from .plan_setup import to_posix_s
from .plan_types import RoutePlan
from .planning import plan
from .request import (
    ForecastInput,
    PlanOptions,
    ProgressHook,
    VoyageRequest,
    with_fields,
)
from .voyage.port_calls import PortCall, parse_port_calls
from .voyage.stage_length import RTA_TOLERANCE_S, check_rta_tolerance_s

# "" = the ship file's performance_model entry, else physics; "physics" (alias "fast") is the
# ship file's physics tabulated for the hot path, "physics-direct" solves it on every leg
SHIP_MODELS = ("", "physics", "fast", "physics-direct", "kwon")
FILE_MODELS = ("profile", "learned")  # "profile:FILE.nc", "learned:FILE.nc"
_DUR = re.compile(r"^\s*(\d+(?:\.\d*)?)\s*([smhd])\s*$")
_EVALS = re.compile(r"^\s*(\d+)\s*(?:ev|evals?|evaluations?)\s*$", re.IGNORECASE)
_UNIT_S = {"s": 1.0, "m": 60.0, "h": 3600.0, "d": 86400.0}


def duration_s(text: str) -> float:
    """'13d', '36h', '90m', '3s' or plain seconds -> seconds."""
    m = _DUR.match(str(text))
    if m:
        return float(m.group(1)) * _UNIT_S[m.group(2)]
    try:
        value = float(text)
    except ValueError:
        raise InvalidVoyageError(
            f"duration {text!r}: use a number with s, m, h or d (e.g. 13d, 3s)") from None
    if not math.isfinite(value):
        raise InvalidVoyageError(f"duration {text!r} is not a finite number")
    return value


@dataclass(frozen=True)
class Budget:
    """Search budget: wall time of the whole plan, or a fixed number of route evaluations
    (equal work whatever the machine: reproducible with a fixed seed)."""

    wall_s: float = 3.0
    evaluations: int = 0  # 0 = stop on wall time

    @staticmethod
    def parse(text: str) -> Budget:
        """'3s' / '90' (seconds of wall time) or '4000ev' / '4000 evals' (route evaluations)."""
        m = _EVALS.match(str(text))
        if m:
            n = int(m.group(1))
            if n < 1:
                raise InvalidVoyageError(f"budget {text!r}: at least 1 evaluation")
            return Budget(math.inf, n)
        wall = duration_s(text)
        if wall <= 0:
            raise InvalidVoyageError(f"budget {text!r} must be positive")
        return Budget(wall, 0)

    def label(self) -> str:
        """The budget as the user writes it."""
        return f"{self.evaluations}ev" if self.evaluations else f"{self.wall_s:g}s"


def parse_rta_s(text: str, depart_s: float) -> float:
    """RTA as an ISO 8601 UTC time or a duration after departure ('13d') -> POSIX s."""
    if re.match(r"^\s*\d+(\.\d*)?\s*[smhd]?\s*$", str(text)):
        return depart_s + duration_s(text)
    return parse_time_s(text, "RTA")


def parse_time_s(text: str, what: str) -> float:
    """ISO 8601 UTC time ('Z' or an offset; naive = UTC) -> POSIX s, naming `what` on error."""
    try:
        return to_posix_s(str(text))
    except ValueError:
        raise InvalidVoyageError(
            f"{what} {text!r} is not an ISO 8601 time such as 2026-03-03T18:00Z") from None


@dataclass(frozen=True)
class PlanRequest:
    """Everything that decides a plan except the forecast (times POSIX s UTC)."""

    origin: str
    destination: str
    depart_s: float
    rta_s: float
    ship: str = "container_4600teu"  # bundled ship name or ship YAML path
    via: tuple[str, ...] = ()
    via_rta_s: tuple[float | None, ...] = ()
    objective: str = "fuel"
    method: str = "seed_ga"
    model: str = ""
    budget: Budget = field(default_factory=Budget)
    seed: int = 0
    stage_hours: float | None = None  # None: derived from the voyage (voyage.stage_length)
    loading: str = ""  # ship file condition or 'T_F,T_A' drafts [m]; '' = the file's default
    economics: Economics = field(default_factory=Economics)
    front_points: int = 9  # plans on the time-fuel front (objective "front")
    port_calls: tuple[PortCall, ...] = ()  # the vias' windows and berth times
    rta_tolerance_s: float = RTA_TOLERANCE_S

    def __post_init__(self) -> None:
        if self.objective not in OBJECTIVES:
            raise InvalidVoyageError(
                f"objective {self.objective!r}: use one of {', '.join(OBJECTIVES)}")
        kind, sep, path = self.model.partition(":")
        if not (self.model in SHIP_MODELS or (kind in FILE_MODELS and sep and path.strip())):
            raise InvalidVoyageError(
                f"ship model {self.model!r}: use physics, physics-direct, kwon, "
                "profile:FILE.nc or learned:FILE.nc")
        if not self.rta_s > self.depart_s:
            raise InvalidVoyageError("the RTA must be after the departure time")
        if not 2 <= self.front_points <= 25:
            raise InvalidVoyageError(f"front points must be 2..25, got {self.front_points}")
        check_rta_tolerance_s(self.rta_tolerance_s)
        for name, value in self.numbers().items():
            require_number(name, value)  # the node's parameter ranges: one table

    def voyage_request(self) -> VoyageRequest:
        """The voyage this request asks for (the planner's typed request)."""
        return VoyageRequest(
            self.origin, self.destination, self.depart_s, self.rta_s, self.ship,
            via=self.via, via_rta_s=self.via_rta_s, port_calls=self.port_calls,
            rta_tolerance_s=self.rta_tolerance_s, objective=self.objective,
            economics=self.economics, ship_model=self.model, loading=self.loading)

    def plan_options(self) -> PlanOptions:
        """How this request is searched: method, budget, seed and stage length."""
        return PlanOptions(method=self.method, budget_s=self.budget.wall_s,
                           max_evaluations=self.budget.evaluations, seed=self.seed,
                           stage_hours=self.stage_hours)

    def numbers(self) -> dict[str, object]:
        """The request's numeric settings under the planner's parameter names."""
        budget = ({"budget_evaluations": self.budget.evaluations} if self.budget.evaluations
                  else {"budget_s": self.budget.wall_s})
        stages = {} if self.stage_hours is None else {"stage_hours": self.stage_hours}
        return {**stages, "rng_seed": self.seed, **budget}


def build_request(*, origin: str, destination: str, depart: str, rta: str,
                  via: Sequence[str] = (), ship: str = "container_4600teu",
                  objective: str = "fuel", method: str = "seed_ga", model: str = "",
                  budget: str = "3s", seed: int = 0, stage_hours: float | None = None,
                  rta_tolerance: str = "5m",
                  loading: str = "", fuel_type: str | None = None,
                  fuel_price_usd_per_t: float | None = None,
                  charter_usd_per_day: float | None = None,
                  front_points: int = 9) -> PlanRequest:
    """A request from user text (raises InvalidVoyageError naming the bad input); `via`
    items are port calls `PORT[@EARLIEST..LATEST][+BERTH_H]` (`voyage.port_calls`)."""
    depart_s = parse_time_s(depart, "departure")
    calls = parse_port_calls(list(via), depart_s)
    if loading.strip():
        from .ship.condition import parse_loading
        from .ship.errors import ShipModelError

        try:
            parse_loading(loading)
        except ShipModelError as exc:
            raise InvalidVoyageError(str(exc)) from None
    return PlanRequest(
        origin.strip(), destination.strip(), depart_s, parse_rta_s(rta, depart_s),
        ship=ship.strip(), via=tuple(c.port for c in calls),
        via_rta_s=tuple(c.latest_s for c in calls), objective=objective, method=method,
        model=model, budget=Budget.parse(budget), seed=int(seed),
        stage_hours=None if stage_hours is None else float(stage_hours),
        loading=loading.strip(),
        economics=Economics(fuel_type, fuel_price_usd_per_t, charter_usd_per_day),
        front_points=int(front_points), port_calls=calls,
        rta_tolerance_s=duration_s(rta_tolerance))


def run_request(req: PlanRequest, forecast: ForecastInput = None, *, cycle_id: str = "",
                seed_pool_dir: str | Path | None = None,
                progress: ProgressHook | None = None, **extra: Any) -> RoutePlan:
    """Plan `req` on `forecast` (a ForecastSampler, a canonical Dataset or None for calm
    water); `extra` sets further request or option fields (land mask, cancel, ...)."""
    request, options = with_fields(req.voyage_request(), req.plan_options(), **extra)
    options = dataclasses.replace(options, cycle_id=cycle_id, seed_pool_dir=seed_pool_dir,
                                  progress=progress)
    return plan(request, options, forecast)
