"""Depth in a plan: the UKC constraint a voyage is planned with, and what the plan reports.

`depth_limits` adds the ship's under-keel clearance constraint to the route limits when
bathymetry is available and says in words what depth the plan uses (or that it has none);
`with_depth_report` puts each leg's shallowest depth and UKC, computed exactly (no cap) along
the final track, into the waypoints and warns about legs no grid covers (the route check
lists the legs that lack clearance).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from shiproute_core.geodesy import direct, inverse
from shiproute_core.units import M_S_PER_KNOT

from .errors import BathymetryError
from .geo.depth import Bathymetry, load_bathymetry
from .plan_types import RoutePlan
from .route.problem import RouteLimits
from .route.under_keel import UnderKeel, under_keel_for_ship

PORT_CLEARANCE_M = 3000.0  # depth next to a berth is the harbour's business, not the grid's
NO_DEPTH = ("depth not checked: no bathymetry grid (give --bathymetry FILE, or install the "
            "Debian package ferret-datasets for the global ETOPO5 grid)")
NO_DEPTH_GIVEN = ("depth not checked: no bathymetry grid given and the global ETOPO5 default "
                  "not asked for (bathymetry files, or default_bathymetry)")


def depth_limits(limits: RouteLimits, spec: Any, bathymetry: Sequence[str | Path] | Bathymetry
                 | None, with_default: bool, margin_m: float
                 ) -> tuple[RouteLimits, list[str]]:
    """Route limits with the UKC constraint (when depth is known) and the plan's words on it."""
    if margin_m < 0:
        raise BathymetryError(f"UKC margin {margin_m} m must not be negative")
    bathy = bathymetry if isinstance(bathymetry, Bathymetry) else load_bathymetry(
        bathymetry or (), with_default=with_default)
    if bathy is None:
        return limits, [NO_DEPTH if with_default else NO_DEPTH_GIVEN]
    if spec is None:
        return limits, ["depth not checked: the ship model has no draft (give a ship file)"]
    uk = under_keel_for_ship(spec, bathy, margin_m)
    note = (f"depth from {bathy.description}; UKC = depth - (draft {uk.draft_m:.1f} m + "
            f"Barrass squat Cb {uk.block_coefficient:.2f} V^2/100 + "
            f"{uk.wave_allowance_per_hs:g} Hs + margin {uk.margin_m:.1f} m); not a constraint "
            "within 10 NM of ports and approach ends (dredged channels no grid resolves: the "
            "route check lists what it finds there)")
    return dataclasses.replace(limits, under_keel=uk), [note]


def _cut_ends(lon0: np.ndarray, lat0: np.ndarray, lon1: np.ndarray, lat1: np.ndarray,
              first: bool, last: bool
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Leg ends with PORT_CLEARANCE_M cut off the voyage's first start and last end."""
    lon0, lat0, lon1, lat1 = (np.array(a, dtype=float) for a in (lon0, lat0, lon1, lat1))
    for k, at_start in ((0, True), (lon0.size - 1, False)):
        if (at_start and not first) or (not at_start and not last) or lon0.size == 0:
            continue
        az, dist = inverse(lon0[k], lat0[k], lon1[k], lat1[k])
        cut = min(PORT_CLEARANCE_M, 0.5 * float(dist))
        if at_start:
            lon0[k], lat0[k] = (float(v) for v in direct(lon0[k], lat0[k], az, cut))
        else:
            back, _ = inverse(lon1[k], lat1[k], lon0[k], lat0[k])
            lon1[k], lat1[k] = (float(v) for v in direct(lon1[k], lat1[k], back, cut))
    return lon0, lat0, lon1, lat1


def track_clearance(uk: UnderKeel, lon: np.ndarray, lat: np.ndarray, stw_m_s: np.ndarray,
                    hs_m: np.ndarray, ports_at_ends: bool = True
                    ) -> tuple[np.ndarray, np.ndarray]:
    """Exact (shallowest depth [m], UKC [m]) of each leg of a polyline; the first and last
    `PORT_CLEARANCE_M` are skipped when the ends are berths."""
    ends = _cut_ends(lon[:-1], lat[:-1], lon[1:], lat[1:], ports_at_ends, ports_at_ends)
    return uk.leg_clearance(*ends, stw_m_s, hs_m, exact=True)


def with_depth_report(plan: RoutePlan, uk: UnderKeel | None, notes: list[str]) -> RoutePlan:
    """The plan with exact per-leg depth/UKC in its waypoints and the depth warnings."""
    warnings = [*plan.warnings, *notes]
    if uk is None or len(plan.waypoints) < 2:
        return dataclasses.replace(plan, warnings=tuple(warnings))
    lon, lat, _ = plan.track()
    wps = plan.waypoints
    stw = np.array([w.stw_kn for w in wps[:-1]]) * M_S_PER_KNOT
    hs = np.array([w.hs_m for w in wps[:-1]])
    depth, ukc = track_clearance(uk, lon, lat, stw, hs)
    new = []
    for k, w in enumerate(wps):
        if k < depth.size:  # FLAG_DEPTH stays the optimiser's (pilotage waters excepted)
            w = dataclasses.replace(w, min_depth_m=float(depth[k]), ukc_m=float(ukc[k]))
        new.append(w)
    unknown = int(np.count_nonzero(np.isnan(depth)))
    if unknown:
        warnings.append(f"depth not checked on {unknown} of {depth.size} legs "
                        "(no bathymetry grid covers them)")
    return dataclasses.replace(plan, waypoints=tuple(new), warnings=tuple(warnings))
