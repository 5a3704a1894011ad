"""The planning API's two inputs, frozen and typed: what voyage to plan (`VoyageRequest`) and
how to search for it (`PlanOptions`). The CLI, the node, the benches, the fleet runner and the
comparison build these and call `planning.plan(request, options, forecast)`."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from datetime import timedelta
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol, TypeAlias, runtime_checkable

import numpy as np

from .ga.loop import GAConfig
from .geo.depth import Bathymetry
from .geo.landmask import LandMask
from .geo.ports import Port
from .geo.zones import Zones
from .method_context import Progress
from .objectives import Economics
from .plan_setup import TimeLike, to_posix_s
from .plan_types import RoutePlan
from .route.clearance import DEFAULT_CLEARANCE
from .route.risk import RiskSpec
from .ship.performance import PerformanceModel
from .ship.spec import ShipSpec
from .voyage.port_calls import PortCall
from .voyage.stage_length import RTA_TOLERANCE_S

if TYPE_CHECKING:
    import xarray as xr


@runtime_checkable
class ForecastSampling(Protocol):
    """A forecast the planner samples (`shiproute_weather`'s `ForecastSampler` contract)."""

    def sample(self, lon_deg: np.ndarray, lat_deg: np.ndarray,
               time_s: np.ndarray) -> dict[str, np.ndarray]:
        """Canonical variables at the points (arrays broadcast to one shape)."""
        ...


@runtime_checkable
class CancelEvent(Protocol):
    """A cancel flag such as `threading.Event`."""

    def is_set(self) -> bool:
        """True once the plan is to stop."""
        ...


# a ship: bundled name, ship YAML path, ship spec, or a ready performance model
ShipInput = str | Path | ShipSpec | PerformanceModel
CancelHook = Callable[[], bool] | CancelEvent
ProgressHook = Callable[[Progress], None]
FileList = tuple[str | Path, ...]
# a forecast: a sampler, a canonical xarray Dataset, or None for calm water
ForecastInput: TypeAlias = "ForecastSampling | xr.Dataset | None"


@dataclass(frozen=True)
class VoyageRequest:
    """What to plan: ports and port calls, times (POSIX s UTC), ship, loading and model,
    objective and economics, and the charts (bathymetry, zones, given approaches) the route
    is checked against. Field meanings are those of `planning.plan_voyage`'s keywords."""

    origin: str | Port
    destination: str | Port
    depart_s: float
    rta_s: float
    ship: ShipInput
    via: tuple[str | Port, ...] = ()
    via_rta_s: tuple[float | None, ...] = ()  # latest arrivals at `via` (None: open)
    port_calls: tuple[PortCall, ...] = ()  # replace `via`: windows and berth times
    rta_tolerance_s: float = RTA_TOLERANCE_S
    objective: str = "fuel"
    economics: Economics | None = None
    ship_model: str = ""  # "" = the ship file's entry; physics, physics-direct, kwon, ...
    loading: str = ""  # ship file condition or 'T_F,T_A' drafts [m]; '' = the file's default
    bathymetry: FileList | Bathymetry | None = None
    default_bathymetry: bool = False
    ukc_margin_m: float = 1.0
    zones: FileList | Zones | None = None
    clearance_nm: float = 0.0
    approaches_given: FileList = ()
    approach_nm: float = 25.0
    approach_rpm: float | None = None
    coastal_passage: bool = True


@dataclass(frozen=True)
class PlanOptions:
    """How to search: method, budget (wall time and/or evaluations), seed, stages, GA
    settings, re-plan state (previous plan, ship position), seed pool, hooks, limits, land
    mask and how the forecast is extended beyond its ends."""

    method: str = "seed_ga"
    budget_s: float = 3.0
    seed: int | np.random.Generator = 0
    stage_hours: float | None = None  # None: derived per leg (voyage.stage_length)
    ga_config: GAConfig | None = None
    stall_generations: int = 0
    max_generations: int = 100_000
    max_evaluations: int = 0  # route evaluations of the whole voyage (0 = none)
    with_baseline: bool = True
    previous_plan: RoutePlan | None = None
    position: tuple[float, float, float] | None = None  # (lat_deg, lon_deg, POSIX s)
    seed_pool_dir: str | Path | None = None
    progress: ProgressHook | None = None
    cancel: CancelHook | None = None
    limits: Mapping[str, float] | None = None  # RouteLimits overrides
    land: LandMask | None = None
    cycle_id: str = ""
    persistence_h: float = 24.0
    climatology: xr.Dataset | None = None
    risk: RiskSpec | str | None = None  # plan on every ensemble member under this measure
    p_hs_max: float | None = None  # chance constraint P(Hs > limit) of a risk-aware plan
    p_late_max: float | None = None  # chance constraint P(late) of a risk-aware plan
    # distance from the coast the search keeps (route.clearance.ClearanceRule; 0: off land)
    open_sea_clearance_nm: float = DEFAULT_CLEARANCE.open_sea_nm
    approach_clearance_nm: float = DEFAULT_CLEARANCE.approach_nm
    approach_zone_nm: float = DEFAULT_CLEARANCE.approach_zone_nm


def voyage_times(depart: TimeLike, rta: TimeLike | timedelta) -> tuple[float, float]:
    """(depart_s, rta_s) from a time and an RTA given as a time or a duration after it."""
    depart_s = to_posix_s(depart)
    rta_s = depart_s + rta.total_seconds() if isinstance(rta, timedelta) else to_posix_s(rta)
    return depart_s, rta_s


def file_list(value: Sequence[str | Path] | str | Path | None) -> FileList | None:
    """A file argument as a tuple of paths (None stays None)."""
    if value is None:
        return None
    if isinstance(value, str | Path):
        return (value,)
    return tuple(value)


def with_fields(request: VoyageRequest, options: PlanOptions,
                **fields: object) -> tuple[VoyageRequest, PlanOptions]:
    """`request` and `options` with `fields` (any `plan_voyage` keyword naming a field of
    either) replaced; file lists become tuples. Raises TypeError for an unknown name."""
    voyage_names = {f.name for f in dataclasses.fields(VoyageRequest)}
    option_names = {f.name for f in dataclasses.fields(PlanOptions)}
    unknown = set(fields) - voyage_names - option_names
    if unknown:
        raise TypeError(f"no request or option field {', '.join(sorted(unknown))}")
    for name in ("bathymetry", "zones", "approaches_given"):
        value = fields.get(name)
        if isinstance(value, list):
            fields[name] = tuple(value)
    # the names were checked above; each field's type is checked where it is used
    voyage: dict[str, Any] = {k: v for k, v in fields.items() if k in voyage_names}
    option: dict[str, Any] = {k: v for k, v in fields.items() if k in option_names}
    return dataclasses.replace(request, **voyage), dataclasses.replace(options, **option)
