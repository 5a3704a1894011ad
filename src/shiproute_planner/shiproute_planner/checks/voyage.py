"""Checks of a voyage before it is planned: ports resolve to water, the ship and its model
exist, the RTA is after the departure, and whether the RTA can be met at all.

An RTA that even the great circle (shorter than any route at sea) cannot meet at the ship's
calm-water speed at maximum RPM is not an error: the plan is made best effort (as early as the
ship can make it) and flagged `FLAG_RTA` with `VoyageCheck.rta_warning` as its reason.
Everything else wrong raises the package's own error naming the input and the reason
(`InvalidVoyageError`, `PortNotFoundError`, `PositionOnLandError`, `UnknownShipError`,
`ShipFileError`, `UnknownMethodError`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from shiproute_core.units import M_PER_NM, M_S_PER_KNOT

from ..errors import InvalidVoyageError
from ..geo.ports import Port, resolve_port
from ..objectives import OBJECTIVES
from .forecast_wire import EARLIEST_TIME_S, LATEST_TIME_S

KNOT_M_S = M_S_PER_KNOT


@dataclass(frozen=True)
class VoyageCheck:
    """A checked voyage: resolved ports, times, ship and whether its RTA can be met."""

    origin: Port
    destination: Port
    depart_s: float | None  # None: not known yet (simulated time before /clock)
    rta_s: float
    ship: Any  # ShipSpec
    great_circle_nm: float
    required_speed_kn: float  # over the great circle, a lower bound of what the RTA needs
    max_speed_kn: float  # calm water at maximum RPM

    @property
    def rta_reachable(self) -> bool:
        """False when even the great circle at full speed arrives after the RTA."""
        return self.required_speed_kn <= self.max_speed_kn

    @property
    def rta_warning(self) -> str:
        """Why the RTA cannot be met ('' when it can)."""
        if self.rta_reachable or self.depart_s is None:
            return ""
        return (f"RTA unreachable: {self.great_circle_nm:.0f} NM (great circle, the shortest "
                f"possible) in {(self.rta_s - self.depart_s) / 3600:.1f} h needs "
                f"{self.required_speed_kn:.1f} kn, the ship makes at most "
                f"{self.max_speed_kn:.1f} kn in calm water; best-effort plan")


def check_position(name: str, lat_deg: float, lon_deg: float) -> str:
    """A 'lat,lon' port text for finite in-range coordinates, or InvalidVoyageError."""
    if not (math.isfinite(lat_deg) and -90.0 <= lat_deg <= 90.0):
        raise InvalidVoyageError(f"{name} latitude {lat_deg!r}; expected -90..90")
    if not (math.isfinite(lon_deg) and -180.0 <= lon_deg <= 360.0):
        raise InvalidVoyageError(f"{name} longitude {lon_deg!r}; expected -180..360")
    return f"{lat_deg:.6f},{lon_deg:.6f}"


def max_calm_speed_kn(spec: Any) -> float:
    """Calm-water speed through the water at the engine's maximum RPM [kn]."""
    from ..ship import SeaState
    from ..ship.fast import fast_model

    perf = fast_model(spec).evaluate(np.array([spec.engine.rpm_max]), np.array([0.0]),
                                     SeaState.calm(1))
    return float(perf.stw_m_s[0]) / M_S_PER_KNOT


def check_voyage(origin: str | Port, destination: str | Port, depart_s: float | None,
                 rta_s: float,
                 ship: Any, *, land: Any = None, objective: str = "fuel",
                 method: str = "seed_ga", ship_model: str = "") -> VoyageCheck:
    """Resolve and check a voyage (see the module docstring); raises on what is invalid."""
    from shiproute_core.geodesy import inverse

    from ..geo.landmask import default_land_mask
    from ..methods import get_method
    from ..ship import ShipSpec, load_ship

    if objective not in OBJECTIVES:
        raise InvalidVoyageError(f"objective {objective!r}; expected one of "
                                 f"{', '.join(OBJECTIVES)}")
    get_method(method)  # UnknownMethodError names the known ones
    for name, t in (("departure time", depart_s), ("RTA", rta_s)):
        if t is not None and not (math.isfinite(t) and EARLIEST_TIME_S <= t <= LATEST_TIME_S):
            raise InvalidVoyageError(f"{name} {t!r} s; expected a UTC time in 1990..2100")
    if depart_s is not None and not rta_s > depart_s:
        raise InvalidVoyageError(f"the RTA ({rta_s:.0f} s) must be after the departure "
                                 f"({depart_s:.0f} s)")
    land = land or default_land_mask()
    ports = [p if isinstance(p, Port) else resolve_port(str(p), land)
             for p in (origin, destination)]
    if isinstance(ship, str) and not ship.strip():
        raise InvalidVoyageError("ship is empty; expected a bundled ship name or a ship file")
    spec = ship if isinstance(ship, ShipSpec) else load_ship(ship)
    check_model_file(ship_model or spec.performance_model)
    a, b = ports
    _, dist_m = inverse(a.lon_deg, a.lat_deg, b.lon_deg, b.lat_deg)
    dist_nm = float(dist_m) / M_PER_NM
    need_kn = 0.0 if depart_s is None else dist_nm / ((rta_s - depart_s) / 3600.0)
    return VoyageCheck(a, b, depart_s, float(rta_s), spec, dist_nm, need_kn,
                       max_calm_speed_kn(spec))


def check_model_file(choice: str) -> None:
    """The ship model a plan would use (the node's ship_model, else the ship file's entry)
    exists: a profile or learned model names a file that is there (ModelFileError if not)."""
    from pathlib import Path

    from ..learned.errors import ModelFileError

    kind, sep, path = choice.strip().partition(":")
    if kind in ("profile", "learned") and sep and not Path(path).is_file():
        raise ModelFileError(f"ship model {choice!r}: {kind} model file {path} does not exist")
