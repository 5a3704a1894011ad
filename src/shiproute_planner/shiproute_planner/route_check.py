"""Check a route as an ECDIS does: land, clearance from land, depth/UKC and no-go zones.

Every leg is sampled along its geodesic (points every `step_m`, ~0.25 NM) and each finding is
reported with the leg, a position and a value. The land test is a point test passed in (GSHHG
polygons at the best resolution installed for `shiproute check`; the planner's own land mask
for the check it runs on every plan); the clearance is the distance from each sample to the
land polygons clipped round the leg.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import shapely
from shiproute_core.geodesy import densify_track, inverse, wrap_lon
from shiproute_core.units import M_PER_NM

from .geo.zones import Zones
from .route.berths import BERTH_RADIUS_M
from .route.track_samples import track_samples
from .route.under_keel import UnderKeel


@dataclass(frozen=True)
class Violation:
    """One finding: what, on which leg (0-based), where, and how much."""

    kind: str  # land | clearance | depth | zone
    leg: int
    lat_deg: float
    lon_deg: float
    value: float
    unit: str
    text: str

    def line(self) -> str:
        """One line for a terminal or a log."""
        return (f"leg {self.leg:3d}  {self.lat_deg:9.5f} {self.lon_deg:10.5f}  {self.kind:9s} "
                f"{self.text}")


@dataclass(frozen=True)
class CheckResult:
    """Violations in leg order and notes on what the check used or only advises."""

    violations: tuple[Violation, ...]
    notes: tuple[str, ...]

    @property
    def ok(self) -> bool:
        """True when nothing is violated."""
        return not self.violations


#: sample spacing along each leg (0.25 NM): the planner's final choice samples its candidates at
#: the same points, so a plan it chooses never fails this check for land between samples
CHECK_STEP_M = M_PER_NM / 4.0


def _leg_points(lon: np.ndarray, lat: np.ndarray, k: int, step_m: float):
    plon, plat = densify_track(lon[k:k + 2], lat[k:k + 2], step_m)
    return np.asarray(plon, dtype=float), np.asarray(plat, dtype=float)


def check_track(lon_deg: np.ndarray, lat_deg: np.ndarray, speed_kn: np.ndarray,
                land_contains: Callable[[np.ndarray, np.ndarray], np.ndarray], *,
                clearance_nm: float = 0.0, land_near: Callable | None = None,
                under_keel: UnderKeel | None = None,
                hs_m: np.ndarray | None = None, zones: Zones | None = None,
                step_m: float = CHECK_STEP_M, port_clearance_m: float = BERTH_RADIUS_M,
                skip_legs: frozenset[int] = frozenset()) -> CheckResult:
    """Check a polyline (continuous longitudes) sailed at `speed_kn` per leg; the first and
    last `port_clearance_m` (berths) are not tested for land, clearance or depth, nor are
    `skip_legs` (fixed passages such as canals, under their authority's rules)."""
    lon = np.unwrap(np.asarray(lon_deg, dtype=float), period=360.0)
    lat = np.asarray(lat_deg, dtype=float)
    n_leg = lon.size - 1
    _, dist = inverse(lon[:-1], lat[:-1], lon[1:], lat[1:])
    dist = np.atleast_1d(np.asarray(dist, dtype=float))
    start = np.concatenate([[0.0], np.cumsum(dist)])
    total = start[-1]
    found: list[Violation] = []
    notes: list[str] = []
    # every leg's samples in one geodesic pass and one land test (a pass per leg cost a
    # re-plan ~50 ms); leg k owns samples first[k] (its start node) .. first[k] + count[k]
    all_lon, all_lat, first, count, all_along = track_samples(lon, lat, dist, step_m)
    tested = (all_along >= port_clearance_m) & (all_along <= total - port_clearance_m)
    for k in skip_legs:
        if 0 <= k < n_leg:
            tested[first[k] + 1:first[k] + count[k]] = False
    all_land = np.zeros(all_lon.size, dtype=bool)
    if tested.any():
        all_land[tested] = np.asarray(land_contains(all_lon[tested], all_lat[tested]),
                                      dtype=bool)
    for k in range(n_leg):
        if k in skip_legs:
            continue
        sl = slice(first[k], first[k] + count[k] + 1)
        keep = tested[sl]
        plon, plat, land = all_lon[sl][keep], all_lat[sl][keep], all_land[sl][keep]
        if plon.size == 0:
            continue
        if land.any():
            i = int(np.argmax(land))
            nm = land.sum() * step_m / M_PER_NM
            found.append(Violation("land", k, float(plat[i]), float(wrap_lon(plon[i])), nm, "NM",
                                   f"crosses land for ~{nm:.2f} NM"))
        elif clearance_nm > 0 and land_near is not None:
            dist_nm = _distance_to_land_nm(plon, plat, clearance_nm, land_near)
            close = dist_nm < clearance_nm
            if close.any():
                i = int(np.argmin(dist_nm))
                found.append(Violation(
                    "clearance", k, float(plat[i]), float(wrap_lon(plon[i])),
                    float(dist_nm[i]), "NM", f"land {dist_nm[i]:.2f} NM off, closer than the "
                    f"required {clearance_nm:g} NM"))
    if under_keel is not None:
        found += _depth_findings(lon, lat, speed_kn, hs_m, under_keel, step_m,
                                 port_clearance_m)
    if zones is not None:
        found_z, notes_z = _zone_findings(lon, lat, dist, zones, step_m)
        found += found_z
        notes += notes_z
    found = [v for v in found if v.leg not in skip_legs]
    found.sort(key=lambda v: (v.leg, v.kind))
    return CheckResult(tuple(found), tuple(notes))


def _distance_to_land_nm(lon: np.ndarray, lat: np.ndarray, clearance_nm: float,
                         land_near: Callable) -> np.ndarray:
    """Distance [NM] from each point to land within a box `clearance_nm` round the points
    (inf beyond), in a local equirectangular frame (lon scaled by cos of the mid latitude;
    within ~3 % for a 200-NM leg at 50 deg)."""
    lon_w = wrap_lon(lon)
    if np.ptp(lon_w) > 180.0:  # leg across the antimeridian: keep one frame
        lon_w = np.where(lon_w < 0, lon_w + 360.0, lon_w)
    mid = float(np.mean(lat))
    c = max(np.cos(np.radians(mid)), 0.05)
    pad_lat, pad_lon = clearance_nm / 60.0 * 1.1, clearance_nm / 60.0 / c * 1.1
    box = (float(lon_w.min() - pad_lon), float(lat.min() - pad_lat),
           float(lon_w.max() + pad_lon), float(lat.max() + pad_lat))
    shift = 360.0 if box[0] >= 180.0 else 0.0
    land = land_near(box[0] - shift, box[1], box[2] - shift, box[3])
    if land.is_empty:
        return np.full(lon.size, np.inf)
    scaled = shapely.transform(land, lambda xy: np.column_stack([(xy[:, 0] + shift) * c,
                                                                 xy[:, 1]]))
    pts = shapely.points(lon_w * c, lat)
    return shapely.distance(pts, scaled) * 60.0


def _depth_findings(lon, lat, speed_kn, hs_m, uk: UnderKeel, step_m: float,
                    port_clearance_m: float) -> list[Violation]:
    from .depth_setup import track_clearance

    n_leg = lon.size - 1
    stw = np.nan_to_num(np.asarray(speed_kn, dtype=float), nan=0.0) * M_PER_NM / 3600.0
    hs = np.zeros(n_leg) if hs_m is None else np.asarray(hs_m, dtype=float)
    depth, ukc = track_clearance(uk, lon, lat, stw, hs, ports_at_ends=port_clearance_m > 0)
    out = []
    for k in np.flatnonzero(ukc < 0):
        plon, plat = _leg_points(lon, lat, int(k), step_m)
        d = uk.bathymetry.depth_m(plon, plat)
        i = int(np.nanargmin(np.where(d <= depth[k] + 1e-6, d, np.inf))) if np.isfinite(
            d).any() else 0
        out.append(Violation("depth", int(k), float(plat[i]), float(wrap_lon(plon[i])),
                             float(ukc[k]), "m",
                             f"depth {depth[k]:.1f} m, UKC {ukc[k]:+.1f} m (needs draft "
                             f"{uk.draft_m:.1f} m + squat at {speed_kn[k]:.1f} kn + wave "
                             f"allowance + margin {uk.margin_m:.1f} m)"))
    return out


def _zone_findings(lon, lat, dist, zones: Zones, step_m: float
                   ) -> tuple[list[Violation], list[str]]:
    samples = int(np.clip(np.ceil(dist.max() / step_m), 16, 2000))
    share = zones.leg_inside(lon[:-1], lat[:-1], lon[1:], lat[1:], samples)
    out, notes = [], []
    for zi, z in enumerate(zones.zones):
        for k in np.flatnonzero(share[zi] > 0):
            nm = float(share[zi, k] * dist[k] / M_PER_NM)
            plon, plat = _leg_points(lon, lat, int(k), step_m)
            x0 = float(np.asarray(z.geometry.bounds)[0])
            inside = shapely.contains_xy(z.geometry, (plon - x0 + 180.0) % 360.0 - 180.0 + x0,
                                         plat)
            i = int(np.argmax(inside)) if np.any(inside) else 0
            if z.hard:
                out.append(Violation("zone", int(k), float(plat[i]), float(wrap_lon(plon[i])),
                                     nm, "NM", f"enters no-go zone {z.name!r} (~{nm:.1f} NM)"))
            else:
                notes.append(f"leg {k}: ~{nm:.1f} NM in avoid-if-possible zone {z.name!r} "
                             f"(penalty {z.penalty_per_nm:g} per NM)")
    return out, notes
