"""Canals as fixed passages: where a voyage's sea lane runs through a canal the ship fits,
the canal becomes a leg of its own, sailed along the canal's line at its transit speed
(pilotage, not optimised); a ship over a canal's limits is routed round (Cape of Good Hope,
Cape Horn, Skagen) by a turning point the plan names.

Limits are the canal authorities' published maxima (Suez Canal Authority rules of
navigation; Panama Canal Authority Neopanamax locks; Wasserstrassen- und Schifffahrtsamt
Nord-Ostsee-Kanal; Corinth Canal S.A.); transit speeds are the canal length over a typical
published transit time (waiting for a convoy or a lock slot not included).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from shiproute_core.units import M_S_PER_KNOT

from .nearest import nearest_node

if TYPE_CHECKING:
    from .evaluation import RouteEvaluation


@dataclass(frozen=True)
class Canal:
    """A canal: its line from one sea entrance to the other, transit speed and limits."""

    name: str
    line: tuple[tuple[float, float], ...]  # (lat, lon) from the first to the second entrance
    transit_kn: float
    max_draft_m: float
    max_beam_m: float
    max_length_m: float
    round_via: tuple[float, float, str]  # (lat, lon, name) of the way round for too-big ships
    # searoute's name of the passage (for its lanes that avoid it; '' when it has none)
    searoute_passage: str = ""
    # line points from .. to sailed at the transit speed; outside them (a gulf or approach
    # channel leading to the canal, a fixed route too) the ship keeps its sea speed
    slow: tuple[int, int] = (0, -1)

    def too_big(self, draft_m: float, beam_m: float, length_m: float) -> str:
        """Why a ship may not transit ('' when it may)."""
        over = [f"{what} {v:.1f} m > {lim:.1f} m" for what, v, lim in (
            ("draft", draft_m, self.max_draft_m), ("beam", beam_m, self.max_beam_m),
            ("length", length_m, self.max_length_m)) if v > lim]
        return "; ".join(over)


CANALS: tuple[Canal, ...] = (
    Canal("Suez Canal", ((27.65, 33.85), (28.20, 33.45), (28.90, 32.95), (29.50, 32.65),
                         (29.87, 32.55), (29.93, 32.57), (30.32, 32.38), (30.58, 32.30),
                         (30.80, 32.32), (31.26, 32.31), (31.35, 32.35)),
          transit_kn=7.5, max_draft_m=20.1, max_beam_m=77.5, max_length_m=400.0,
          round_via=(-36.5, 20.0, "off Cape Agulhas (Cape of Good Hope route)"), slow=(4, 10),
          searoute_passage="suez"),
    Canal("Panama Canal (Neopanamax locks)", ((9.40, -79.92), (9.27, -79.92), (9.15, -79.85),
                                             (9.12, -79.70), (9.05, -79.66), (9.02, -79.60),
                                             (8.95, -79.56), (8.88, -79.52)),
          transit_kn=5.0, max_draft_m=15.2, max_beam_m=51.25, max_length_m=366.0,
          round_via=(-57.0, -67.0, "south of Cape Horn"), searoute_passage="panama"),
    Canal("Kiel Canal", ((53.88, 9.10), (53.90, 9.15), (54.10, 9.40), (54.30, 9.68),
                         (54.37, 10.15), (54.45, 10.20)),
          transit_kn=6.5, max_draft_m=9.5, max_beam_m=32.5, max_length_m=235.0,
          round_via=(57.95, 10.80, "off Skagen")),
    Canal("Corinth Canal", ((37.96, 22.93), (37.94, 22.96), (37.915, 23.00), (37.90, 23.02)),
          transit_kn=4.0, max_draft_m=7.3, max_beam_m=17.6, max_length_m=150.0,
          round_via=(36.15, 22.50, "south of Cape Matapan (round the Peloponnese)")),
)

NEAR_M = 15_000.0  # a lane "uses" a canal when it passes both its entrances this close


def canals_on_lane(lon_deg: np.ndarray, lat_deg: np.ndarray) -> list[tuple[int, Canal, bool]]:
    """Canals a sea-lane polyline passes through: (index of the lane point nearest the first
    entrance met, canal, reversed) in lane order; `reversed` when sailed exit to entry."""
    from shiproute_core.geodesy import densify_track

    found = []
    lon, lat = densify_track(np.unwrap(np.asarray(lon_deg, dtype=float), period=360.0),
                             np.asarray(lat_deg, dtype=float), 2000.0)
    lon, lat = np.asarray(lon, dtype=float), np.asarray(lat, dtype=float)
    for canal in CANALS:
        ends = (canal.line[canal.slow[0]], canal.line[canal.slow[1]])
        idx = []
        for e_lat, e_lon in ends:
            near = nearest_node(lon, lat, e_lon, e_lat, NEAR_M)
            if near is None:
                break
            idx.append(near[0])
        if len(idx) == 2:
            found.append((min(idx), canal, idx[0] > idx[1]))
    return sorted(found, key=lambda f: f[0])


def canal_line(canal: Canal, reverse: bool) -> tuple[np.ndarray, np.ndarray]:
    """(lon, lat) of the canal line in sailing order."""
    pts = canal.line[::-1] if reverse else canal.line
    return np.array([p[1] for p in pts]), np.array([p[0] for p in pts])


def route_canals(ports: list, spec, via_rta: list) -> tuple[list, dict[int, tuple[Canal, bool]],
                                                             list, list[str]]:
    """Ports with canal entrances/exits (or ways round) inserted where the sea lane between
    two ports runs through a canal; returns (ports, {leg index: (canal, reversed)}, via RTAs
    aligned to the new ports, notes for the plan)."""
    from ..geo.ports import Port
    from ..geo.sea_lanes import sea_lane_between

    draft = beam = length = 0.0
    if spec is not None:
        c, h = spec.condition, spec.hull
        draft, beam, length = max(c.draft_fore_m, c.draft_aft_m), h.breadth_m, h.lpp_m
    rtas = list(via_rta) + [None] * (len(ports) - 2 - len(via_rta))
    out, legs, notes = [ports[0]], {}, []
    out_rta: list[float | None] = []
    for k in range(len(ports) - 1):
        a, b = ports[k], ports[k + 1]
        coords = sea_lane_between(a.lon_deg, a.lat_deg, b.lon_deg, b.lat_deg)
        found = canals_on_lane(coords[:, 0], coords[:, 1]) if coords is not None and len(
            coords) > 1 else []
        for _, canal, rev in found:
            why = canal.too_big(draft, beam, length)
            if why:
                round_lat, round_lon, where = canal.round_via
                turn = Port(f"turning point {where}", "", round_lat, round_lon)
                extra = _keep_clear(out[-1], turn, b, canal)
                out += extra
                out_rta += [None] * len(extra)
                notes.append(f"{canal.name}: the ship is over its limits ({why}); routed "
                              f"round via {where}" + "".join(
                                  f"; {p.name} ({p.lat_deg:.1f}, {p.lon_deg:.1f})"
                                  for p in extra if p is not turn))
                continue
            canal = joined_at_ports(canal, rev, a, b)
            lon, lat = canal_line(canal, rev)
            legs[len(out)] = (canal, rev)  # the whole fixed line: lead-in, canal, lead-out
            out.append(Port(f"{canal.name} entrance", "", float(lat[0]), float(lon[0])))
            out.append(Port(f"{canal.name} exit", "", float(lat[-1]), float(lon[-1])))
            out_rta += [None, None]
            notes.append(f"{canal.name}: transit as a fixed passage at {canal.transit_kn:g} kn "
                         f"(limits draft {canal.max_draft_m:g} m, beam {canal.max_beam_m:g} m, "
                         f"length {canal.max_length_m:g} m; convoy or lock waiting not "
                         "included)")
        out.append(b)
        if k < len(ports) - 2:
            out_rta.append(rtas[k])
    return out, legs, out_rta, notes


def joined_at_ports(canal: Canal, reverse: bool, a, b) -> Canal:
    """The canal with its lead-in (or lead-out) cut at the line point nearest to a port
    beside it: a ship from Ain Sokhna, on the Gulf of Suez, joins the Suez Canal's line
    there instead of sailing 150 NM down the gulf to its entrance and back. `a` is the port
    the transit starts from, `b` the one it heads for; the canal proper is never cut."""
    import dataclasses

    from shiproute_core.geodesy import spherical_m

    lat = np.array([p[0] for p in canal.line])
    lon = np.array([p[1] for p in canal.line])
    last = lat.size - 1
    s0, s1 = canal.slow[0] % lat.size, canal.slow[1] % lat.size
    first_side, last_side = (b, a) if reverse else (a, b)  # ports at line[0] and line[-1]
    lo = int(np.argmin(spherical_m(lon, lat, first_side.lon_deg, first_side.lat_deg)))
    hi = int(np.argmin(spherical_m(lon, lat, last_side.lon_deg, last_side.lat_deg)))
    lo = lo if 0 < lo <= s0 else 0
    hi = hi if s1 <= hi < last else last
    if lo == 0 and hi == last:
        return canal
    return dataclasses.replace(canal, line=canal.line[lo:hi + 1], slow=(s0 - lo, s1 - lo))


def _lane_through(a, b, canal: Canal) -> bool:
    """True when the sea lane from port a to port b runs through `canal`."""
    from ..geo.sea_lanes import sea_lane_between

    coords = sea_lane_between(a.lon_deg, a.lat_deg, b.lon_deg, b.lat_deg)
    return coords is not None and len(coords) > 1 and any(
        c is canal for _, c, _ in canals_on_lane(coords[:, 0], coords[:, 1]))


def _keep_clear(a, turn, b, canal: Canal, depth: int = 3) -> list:
    """Turning points from a to b round `canal` (the canal's own way round first): where the
    sea lane between two of them still runs through the canal (the shortest way from the Gulf
    of Mexico to Cape Horn is through Panama), the point of searoute's lane avoiding the canal
    that lies farthest from the lane through it is added, up to `depth` times."""
    from ..geo.ports import Port

    points = [a, turn, b]
    for _ in range(depth):
        k = next((k for k in range(len(points) - 1)
                  if _lane_through(points[k], points[k + 1], canal)), None)
        if k is None or not canal.searoute_passage:
            break
        way = _farthest_way_round(points[k], points[k + 1], canal.searoute_passage)
        if way is None:
            break
        lat, lon = way
        points.insert(k + 1, Port(f"turning point keeping clear of the {canal.name}", "",
                                  lat, lon))
    return points[1:-1]


def _farthest_way_round(a, b, passage: str) -> tuple[float, float] | None:
    """(lat, lon) of the point of searoute's lane from a to b that avoids `passage` lying
    farthest from the lane that uses it; None without such a lane."""
    from shiproute_core.geodesy import densify_track, spherical_m

    from ..geo.sea_lanes import sea_lane_between

    ends = (a.lon_deg, a.lat_deg, b.lon_deg, b.lat_deg)
    around, through = sea_lane_between(*ends, avoid=(passage,)), sea_lane_between(*ends)
    if (around is None or through is None or around.ndim != 2 or len(around) < 3
            or through.ndim != 2 or len(through) < 2):
        return None
    t_lon, t_lat = (np.asarray(v, dtype=float) for v in densify_track(
        through[:, 0], through[:, 1], 50_000.0))
    gap = [float(spherical_m(t_lon, t_lat, lon, lat).min()) for lon, lat in around]
    k = int(np.argmax(gap))
    return float(around[k, 1]), float(around[k, 0])


def sail_canal(env, canal: Canal, reverse: bool, depart_s: float, limits, stage_s: float,
               sea_rpm: float | None = None):
    """Sail a canal's line from `depart_s`: (lead-in evaluation or None, canal evaluation,
    lead-out evaluation or None, canal RPM, problem). The canal proper is sailed at the RPM of
    its transit speed in calm water, a gulf or channel leading to it at `sea_rpm`. Depth and
    zones are the canal authority's business inside the canal (its draft limit was checked),
    checked as usual on the lead-in and lead-out; land is not tested on the fixed line."""
    import contextlib
    import dataclasses

    from ..ship import SeaState
    from .approach import Approach, sail_approach
    from .problem import RouteProblem

    lon, lat = canal_line(canal, False)
    i0, i1 = canal.slow[0] % lon.size, canal.slow[1] % lon.size
    pieces = [(lon[:i0 + 1], lat[:i0 + 1], False), (lon[i0:i1 + 1], lat[i0:i1 + 1], True),
              (lon[i1:], lat[i1:], False)]
    if reverse:
        pieces = [(lo[::-1], la[::-1], slow) for lo, la, slow in pieces[::-1]]
    inside = dataclasses.replace(limits, under_keel=None, zones=None)
    speed = canal.transit_kn * M_S_PER_KNOT
    rpm = 0.5 * (inside.rpm_min + inside.rpm_max)
    if hasattr(env.model, "rpm_for_speed"):
        with contextlib.suppress(ValueError, ArithmeticError):  # else mid-range RPM
            rpm = float(env.model.rpm_for_speed(np.array([speed]), np.array([0.0]),
                                                SeaState.calm(1))[0])
    rpm = float(np.clip(rpm, inside.rpm_min, inside.rpm_max))
    out: list[RouteEvaluation | None] = []
    t = depart_s
    for lo, la, slow in pieces:
        if lo.size < 2:
            out.append(None)
            continue
        ev = sail_approach(env, Approach(lo, la), rpm if slow else (sea_rpm or rpm), t,
                           inside if slow else limits)
        out.append(ev)
        t = float(ev.eta_s[0])
    c_lon, c_lat = pieces[1][0], pieces[1][1]
    problem = RouteProblem(float(c_lon[0]), float(c_lat[0]), float(c_lon[-1]),
                           float(c_lat[-1]), depart_s, depart_s + 30 * 86400.0, inside,
                           stage_s=stage_s, dep_name=f"{canal.name} entrance",
                           arr_name=f"{canal.name} exit")
    return out[0], out[1], out[2], rpm, problem
