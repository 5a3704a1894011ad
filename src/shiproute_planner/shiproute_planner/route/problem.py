"""One voyage leg as an optimisation problem: ports, times, stages, limits, objective."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from shiproute_core.geodesy import unwrap_near

from ..errors import InvalidVoyageError
from ..objectives import OBJECTIVES
from .clearance import ClearanceRule

if TYPE_CHECKING:
    from ..geo.zones import Zones
    from .under_keel import UnderKeel

STAGE_FIT_TOLERANCE = 1e-9  # stages: a window this much (relative) over whole stages is whole


@dataclass(frozen=True)
class RouteLimits:
    """Constraint limits; None disables a check. Seakeeping criteria as the thesis: 4/7/25 %."""

    rpm_min: float
    rpm_max: float
    max_heading_change_deg: float = 60.0  # per stage, also at the turn onto the final leg
    first_heading_span_deg: float = 150.0  # first heading within +-span of the great circle
    lat_bound_deg: float = 70.0  # nodes must stay within +-lat_bound
    max_hs_m: float | None = None
    max_wind_m_s: float | None = None
    p_slamming_max: float = 0.04
    p_deck_wetness_max: float = 0.07
    p_propeller_emergence_max: float = 0.25
    # IMO MSC.1/Circ.1228 checks enforced as constraints; the thesis uses surf-riding/broaching
    # and parametric roll ("synchronous_roll", "high_wave_group" may be added)
    imo_checks: tuple[str, ...] = ("surf_riding", "parametric_roll")
    engine_limit: bool = True
    # depth constraint (route.under_keel.UnderKeel); None: depth not checked
    under_keel: UnderKeel | None = field(default=None, compare=False)
    # no-go / avoid zones (geo.zones.Zones): hard ones constrain, penalty ones cost
    zones: Zones | None = field(default=None, compare=False)
    # distance from the coast the GA's land walk keeps (route.clearance)
    clearance: ClearanceRule = field(default_factory=ClearanceRule)


@dataclass(frozen=True)
class RouteProblem:
    """A leg from `dep` to `arr` leaving at `depart_s` (POSIX s) with arrival by `rta_s`.

    Longitudes live in a continuous frame: `arr_lon_deg` is unwrapped to within 180 degrees of
    `dep_lon_deg`, so a trans-Pacific leg runs from 129 E to 241.7 E without a seam.
    """

    dep_lon_deg: float
    dep_lat_deg: float
    arr_lon_deg: float
    arr_lat_deg: float
    depart_s: float
    rta_s: float
    limits: RouteLimits
    stage_s: float = 12 * 3600.0
    n_stages: int = 0  # 0: derived from the time window
    objective: str = "fuel"
    # co2 / cost objectives: per_t_fuel x fuel [t] + per_h x time under way [h]
    objective_per_t_fuel: float = 1.0
    objective_per_h: float = 0.0
    land_spacing_deg: float = 0.05
    port_clearance_m: float = 3000.0  # land within this distance of the ports is not checked
    dep_name: str = ""
    arr_name: str = ""
    extra: dict = field(default_factory=dict, compare=False, hash=False)

    def __post_init__(self) -> None:
        if self.objective not in OBJECTIVES:
            raise InvalidVoyageError(
                f"objective {self.objective!r} is not one of {', '.join(OBJECTIVES)}"
            )
        if not self.rta_s > self.depart_s:
            raise InvalidVoyageError(
                f"RTA ({self.rta_s:.0f} s) must be after the departure ({self.depart_s:.0f} s)"
            )
        if self.stage_s <= 0:
            raise InvalidVoyageError(f"stage duration {self.stage_s} s must be positive")
        object.__setattr__(
            self, "arr_lon_deg", float(unwrap_near(self.arr_lon_deg, self.dep_lon_deg))
        )
        if self.n_stages <= 0:
            # the final connection gets (0, 1] stage of time; a window of a whole number of
            # stages by intent (a derived stage length) must not read as a hair more in
            # floating point, which would leave the connection no time at all
            window = self.rta_s - self.depart_s
            stages = math.ceil(window / self.stage_s - STAGE_FIT_TOLERANCE) - 1
            object.__setattr__(self, "n_stages", max(1, stages))
        lim = self.limits
        if not lim.rpm_max > lim.rpm_min > 0:
            raise InvalidVoyageError(
                f"RPM range {lim.rpm_min}..{lim.rpm_max} is empty or not positive"
            )

    @property
    def n_var(self) -> int:
        """Number of genes: n headings + (n + 1) RPMs."""
        return 2 * self.n_stages + 1
