"""Ensemble scenarios: a storm scenario's storm perturbed member by member, the spread growing
with lead time the way medium-range ensembles' cyclone spread grows.

Spread model (per member k a fixed standard-normal draw z_k for each of four perturbations,
so a member is one coherent alternative storm; member 0 is the unperturbed control):
- timing (along-track position): the storm runs ahead of / behind the control by
  z_t x 1.75 h per day of lead time. At a typical extratropical translation of ~40 km/h this
  is ~70 km/day along the track, the growth of ECMWF's cyclone position errors (< 200 km at
  day 3, < 350 km at day 5: ECMWF, "Known IFS forecasting issues", tropical cyclones); most of
  the ensemble error of extratropical storm positions lies in propagation speed rather than
  direction (Froude, Mon. Wea. Rev. 137, 2009; Froude, Bengtsson & Hodges, Mon. Wea. Rev.
  135, 2007);
- cross-track position: z_c x 40 km per day of lead, perpendicular to the motion (smaller
  than along-track for the same reason);
- intensity: the pressure deficit scaled by exp(z_i x 0.06 per day of lead), capped at
  +-35 %: ensembles spread more in intensity than in position (Froude et al. 2007);
- size: the radius of maximum wind scaled by exp(z_r x 0.03 per day of lead).
The background flow and swell are the control's in every member (the spread of these
scenarios is the storm's). Lead time counts from the cycle's reference time.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .synth_wind import TrackPoint

KM_PER_DEG = 111.2  # km per degree of latitude (mean)


@dataclass(frozen=True)
class EnsembleSpread:
    """Growth per day of lead time of each perturbation's standard deviation."""

    timing_h_per_day: float = 1.75
    cross_km_per_day: float = 40.0
    intensity_per_day: float = 0.06
    intensity_cap: float = 0.35
    rmax_per_day: float = 0.03


def member_draws(members: int, seed: int) -> np.ndarray:
    """(members, 4) standard-normal draws (timing, cross, intensity, size); member 0 zero."""
    z = np.random.default_rng(seed).standard_normal((members, 4))
    z[0] = 0.0
    return z


def _heading_rad(track: list[TrackPoint], k: int) -> float:
    """Direction of motion (rad from north) at track point k (central differences)."""
    a, b = track[max(k - 1, 0)], track[min(k + 1, len(track) - 1)]
    dx = (b.lon_deg - a.lon_deg) * math.cos(math.radians(0.5 * (a.lat_deg + b.lat_deg)))
    return math.atan2(dx, b.lat_deg - a.lat_deg)


def perturbed_track(track: list[TrackPoint], z: np.ndarray, reference_h: float,
                    spread: EnsembleSpread = EnsembleSpread()) -> list[TrackPoint]:
    """One member's storm track: `track` (hours since the epoch) perturbed by draws `z`
    (timing, cross, intensity, size), each growing linearly with lead time since
    `reference_h` (hours since the epoch)."""
    out = []
    for k, p in enumerate(track):
        days = max(p.hours - reference_h, 0.0) / 24.0
        shift_h = z[0] * spread.timing_h_per_day * days
        cross_km = z[1] * spread.cross_km_per_day * days
        heading = _heading_rad(track, k)
        dlat = -cross_km * math.sin(heading) / KM_PER_DEG  # to the right of the motion
        dlon = cross_km * math.cos(heading) / (KM_PER_DEG * math.cos(math.radians(p.lat_deg)))
        scale = math.exp(float(np.clip(z[2] * spread.intensity_per_day * days,
                                       -spread.intensity_cap, spread.intensity_cap)))
        out.append(TrackPoint(p.hours - shift_h, p.lat_deg + dlat, p.lon_deg + dlon,
                              p.dp_hpa * scale, p.rmax_km * math.exp(
                                  z[3] * spread.rmax_per_day * days), p.holland_b))
    return out


def spread_summary(spread: EnsembleSpread = EnsembleSpread()) -> str:
    """The spread model in one line (dataset attribute and README)."""
    return (f"storm timing sd {spread.timing_h_per_day:g} h/day of lead, cross-track sd "
            f"{spread.cross_km_per_day:g} km/day, intensity sd {spread.intensity_per_day:.0%}"
            f"/day (cap {spread.intensity_cap:.0%}), Rmax sd {spread.rmax_per_day:.0%}/day; "
            "member 0 control")


@dataclass(frozen=True)
class EnsembleSpec:
    """An ensemble scenario: `members` perturbations of the storm of scenario `base`, on a
    coarser grid than the deterministic scenarios (memory: members x fields)."""

    base: str
    members: int
    spacing_deg: float
    step_h: float
    seed: int
    description: str


def member_fields(base: object, spec: EnsembleSpec, lat: np.ndarray, lon: np.ndarray,
                  hours: np.ndarray, reference_h: float) -> list[dict[str, np.ndarray]]:
    """Every member's canonical fields (time, lat, lon) for hours since the epoch; `base`
    is the deterministic `ScenarioSpec` (season, swell, track, seed)."""
    from .fields import build_fields  # numba-heavy: only when generating

    z = member_draws(spec.members, spec.seed)
    out = []
    for k in range(spec.members):
        track = perturbed_track(base.track, z[k], reference_h)  # type: ignore[attr-defined]
        rng = np.random.default_rng(base.seed)  # type: ignore[attr-defined]
        out.append(build_fields(base.season, base.swell, track, rng,  # type: ignore[attr-defined]
                                lat, lon, hours))
    return out


def storm_centres(base: object, spec: EnsembleSpec, reference_h: float
                  ) -> list[list[TrackPoint]]:
    """Each member's storm track (for plots: the route over the members' storms)."""
    z = member_draws(spec.members, spec.seed)
    return [perturbed_track(base.track, z[k], reference_h)  # type: ignore[attr-defined]
            for k in range(spec.members)]
