"""A SetVoyage request checked against the node's current voyage (ROS-free).

The request's empty fields keep the current values; the result is the parameters to set and
the answer's message, or the package's error naming what is wrong (`checks.voyage`).
"""

from __future__ import annotations

from dataclasses import dataclass
from datetime import UTC, datetime

from .checks.voyage import VoyageCheck, check_position, check_voyage
from .errors import InvalidVoyageError
from .geo.ports import Port
from .voyage.node_calls import port_calls_parameter
from .voyage.port_calls import PortCall, check_port_call
from .voyage_params import parse_utc


@dataclass(frozen=True)
class VoyageChange:
    """What a SetVoyage request changes in the node's voyage (empty text / zero RTA = keep the
    current one); the planning API's own request is `request.VoyageRequest`."""

    destination: str
    destination_lat_deg: float
    destination_lon_deg: float
    rta_s: float
    ship: str
    objective: str
    port_calls: tuple[PortCall, ...] = ()  # replaces the current calls (empty: direct)


@dataclass(frozen=True)
class CheckedVoyage:
    """A valid voyage: the node parameters to set and the answer's message."""

    parameters: dict[str, object]
    message: str
    check: VoyageCheck


def _parse(name: str, text: str) -> float:
    """An ISO 8601 UTC time, or InvalidVoyageError naming the input."""
    try:
        return parse_utc(text)
    except (ValueError, OverflowError) as err:
        raise InvalidVoyageError(f"{name} {text!r} is not an ISO 8601 UTC time: {err}") from err


def _iso(t_s: float) -> str:
    return datetime.fromtimestamp(t_s, UTC).isoformat().replace("+00:00", "Z")


def check_voyage_request(req: VoyageChange, *, origin: str, ship: str, objective: str,
                         method: str, rta: str, position: tuple[float, float, float] | None,
                         departure_time: str, clock_s: float,
                         ship_model: str = "") -> CheckedVoyage:
    """Check `req` with the current voyage's values for what it leaves empty. The voyage
    starts at the ship's position and time when one is known, else at `origin` at
    `departure_time` (or the clock)."""
    dest = req.destination.strip() or check_position(
        "destination", req.destination_lat_deg, req.destination_lon_deg)
    rta_s = req.rta_s if req.rta_s != 0.0 else _parse("rta", rta)
    start: str | Port = origin
    depart_s: float | None = None
    if position is not None:
        start = Port("ship position", "", position[0], position[1])
        depart_s = position[2]
    elif departure_time.strip():
        depart_s = _parse("departure_time", departure_time)
    elif clock_s > 0:
        depart_s = clock_s
    check = check_voyage(start, dest, depart_s, rta_s, req.ship.strip() or ship,
                         objective=req.objective.strip() or objective, method=method,
                         ship_model=ship_model)
    calls = check_calls(req.port_calls, depart_s, rta_s)
    params: dict[str, object] = {"destination": dest,
                                 "port_calls": port_calls_parameter(calls)}
    if req.rta_s != 0.0:
        params["rta"] = _iso(rta_s)
    if req.ship.strip():
        params["ship"] = req.ship.strip()
    if req.objective.strip():
        params["objective"] = req.objective.strip()
    text = (f"voyage to {check.destination.name} set: RTA {_iso(rta_s)}, "
            f"{check.great_circle_nm:.0f} NM great circle from {check.origin.name}")
    if calls:
        text += f"; calling at {', '.join(c.port for c in calls)}"
    if check.rta_warning:
        text += f"; {check.rta_warning}, flagged FLAG_RTA"
    return CheckedVoyage(params, text, check)


def check_calls(calls: tuple[PortCall, ...], depart_s: float | None,
                rta_s: float) -> tuple[PortCall, ...]:
    """Port calls whose ports resolve to water and whose windows are well formed (within the
    voyage), else InvalidVoyageError / PortNotFoundError naming the call."""
    from .geo.landmask import default_land_mask
    from .geo.ports import resolve_port

    land = default_land_mask()
    for call in calls:
        if not call.port:
            raise InvalidVoyageError("a port call names no port")
        check_port_call(call, depart_s if depart_s is not None else -1e18)
        for what, t in (("earliest", call.earliest_s), ("latest", call.latest_s)):
            if t is not None and t > rta_s:
                raise InvalidVoyageError(f"port call {call.port}: {what} arrival {_iso(t)} is "
                                         f"after the RTA {_iso(rta_s)}")
        resolve_port(call.port, land)
    return calls
