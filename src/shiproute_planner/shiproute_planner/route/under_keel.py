"""Under-keel clearance per leg: water depth - (draft + squat + wave allowance + margin).

Squat follows Barrass's simplified formula for the maximum squat [m] of a ship at speed
through the water V [kn] with block coefficient Cb: Cb V^2 / 100 in open water and twice that
in a confined channel (C. B. Barrass, "Ship Squat and Interaction", Witherby 2004; e.g.
Cb 0.9 at 12 kn -> 1.30 m in open water). The wave allowance is a share of the significant
wave height for heave, pitch and roll (default Hs / 2, a common rule for exposed approaches);
the margin is the company's static UKC on top.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from shiproute_core.units import M_S_PER_KNOT

from ..geo.depth import Bathymetry
from ..geo.depth_scan import capped_min_depth_m, prepare


def barrass_squat_m(block_coefficient: float, stw_m_s: np.ndarray | float,
                    confined: bool = False) -> np.ndarray:
    """Maximum squat [m]: Cb V^2 / 100 (V in knots), doubled in a confined channel."""
    v_kn = np.maximum(np.asarray(stw_m_s, dtype=float), 0.0) / M_S_PER_KNOT
    return block_coefficient * v_kn ** 2 / (50.0 if confined else 100.0)


@dataclass(frozen=True, eq=False)
class UnderKeel:
    """Depth constraint of one ship in one loading condition."""

    bathymetry: Bathymetry
    draft_m: float  # deepest draft of the loading condition
    block_coefficient: float
    margin_m: float = 1.0
    wave_allowance_per_hs: float = 0.5
    confined: bool = False

    def __post_init__(self) -> None:
        if not (0.5 <= self.draft_m <= 40.0):
            raise ValueError(f"draft {self.draft_m} m is outside 0.5-40 m")
        if not (0.3 <= self.block_coefficient <= 1.0):
            raise ValueError(f"block coefficient {self.block_coefficient} is outside 0.3-1.0")
        if self.margin_m < 0 or self.wave_allowance_per_hs < 0:
            raise ValueError("UKC margin and wave allowance must not be negative")

    def required_depth_m(self, stw_m_s: np.ndarray, hs_m: np.ndarray) -> np.ndarray:
        """Depth [m] a leg needs: draft + squat at its speed + wave allowance + margin."""
        hs = np.nan_to_num(np.asarray(hs_m, dtype=float), nan=0.0)
        return (self.draft_m + barrass_squat_m(self.block_coefficient, stw_m_s, self.confined)
                + self.wave_allowance_per_hs * hs + self.margin_m)

    def leg_clearance(self, lon0: np.ndarray, lat0: np.ndarray, lon1: np.ndarray,
                      lat1: np.ndarray, stw_m_s: np.ndarray, hs_m: np.ndarray,
                      exact: bool = False) -> tuple[np.ndarray, np.ndarray]:
        """(shallowest depth [m], UKC [m]) per leg. UKC = depth - (draft + squat) - wave
        allowance - margin; negative means too shallow. Without `exact` the depth is capped
        at the leg's required depth (a UKC >= 0 then reads 0: enough for a constraint and
        much cheaper in deep water). NaN where no grid covers the leg."""
        need = self.required_depth_m(stw_m_s, hs_m)
        if exact:
            depth = self.bathymetry.segment_min_depth_m(lon0, lat0, lon1, lat1, np.inf)
        else:  # same result, open water crossed in jumps, legs over the planner's threads
            depth = capped_min_depth_m(self.bathymetry, lon0, lat0, lon1, lat1, need)
        return depth, depth - need


def under_keel_for_ship(spec, bathymetry: Bathymetry, margin_m: float = 1.0,
                        wave_allowance_per_hs: float = 0.5) -> UnderKeel:
    """UKC constraint of a ship file's loading condition: deepest draft, block coefficient
    from displacement / (rho Lwl B T_mean) with rho = 1.025 t/m3."""
    cond, hull = spec.condition, spec.hull
    cb = cond.displacement_t / 1.025 / (hull.lwl_m * hull.breadth_m * spec.mean_draft_m)
    uk = UnderKeel(bathymetry, max(cond.draft_fore_m, cond.draft_aft_m), float(cb),
                   margin_m, wave_allowance_per_hs)
    # the optimiser's scan rasters for what the ship needs in calm water up to full speed
    # (25 kn) in 6 m seas, built once per bathymetry (a plan at sea may need more)
    calm = float(uk.required_depth_m(np.zeros(1), np.zeros(1))[0])
    rough = float(uk.required_depth_m(np.array([25.0 * M_S_PER_KNOT]), np.array([6.0]))[0])
    prepare(bathymetry, calm, rough)
    return uk
