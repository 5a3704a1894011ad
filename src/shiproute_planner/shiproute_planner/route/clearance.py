"""The clearance from the coast a route keeps: per sea-area type, as the optimiser's constraint.

Open sea keeps `open_sea_nm`; within `approach_zone_nm` of either end of the optimised span
(port or pilot station, strait passage exit, the ship's position on a re-plan) the route keeps
`approach_nm`; within `approach_nm` + `FREE_MARGIN_NM` of an end only land itself counts
(pilot stations and a ship's position can lie close to shore). Narrow water, wherever it is,
keeps at most the approach clearance: where the room raster (`geo.narrow_water`: the water
within ~10 NM never lies farther from a coast than this lower bound) is below the open-sea
clearance + `NARROW_MARGIN_NM`, a ship keeping the open-sea clearance would have a lane of
less than 2 x `NARROW_MARGIN_NM`; straits, sounds and island passages are found by their
geometry, not from a list. Below `TIGHT_ROOM_NM` (no water within ~10 NM lies outside the
coastal band of level 0: channels narrower than ~10 NM such as Kanmon, Uraga Suido, the
Bosphorus) a straight stage leg cannot follow the full-resolution coast; the search tests
those stretches on its intermediate coastline and the final repair threads them (`search`
False: the check measures them with the approach clearance).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError

FREE_MARGIN_NM = 0.5
NARROWS_REACH_NM = 5.0  # round a narrows point: narrow water (as `geo.narrow_water`'s reach)
NARROW_MARGIN_NM = 1.0  # room below open sea + this: narrow water (approach clearance)
TIGHT_ROOM_NM = 1.0  # room below this: the search's intermediate coastline decides
EPS_NM = 0.05  # the walk's step where a route hugs its clearance (it keeps c - EPS_NM)
OPEN_SEA_RANGE_NM = (0.0, 5.0)
APPROACH_RANGE_NM = (0.0, 3.0)
APPROACH_ZONE_RANGE_NM = (0.0, 200.0)


@dataclass(frozen=True)
class ClearanceRule:
    """Distances from land [NM] a route keeps, by where it is."""

    # 2 NM in open sea (the example); narrows the room raster reads as open sea
    # because wide water lies within 10 NM of them are found by the sea lane's repair
    # (`narrows`) or, for the Strait of Magellan, are a strait passage (`straits.STRAITS`)
    open_sea_nm: float = 2.0
    approach_nm: float = 0.5  # straits, narrow water and approaches
    approach_zone_nm: float = 10.0
    # (lon, lat) [deg] of points where no detour of the sea lane keeps the open-sea clearance
    # (`route.lane_narrows`): water within NARROWS_REACH_NM of them is narrow water
    narrows: tuple[tuple[float, float], ...] = ()

    def __post_init__(self) -> None:
        for name, (lo, hi) in (("open_sea_nm", OPEN_SEA_RANGE_NM),
                               ("approach_nm", APPROACH_RANGE_NM),
                               ("approach_zone_nm", APPROACH_ZONE_RANGE_NM)):
            value = getattr(self, name)
            if not (isinstance(value, int | float) and math.isfinite(value)
                    and lo <= value <= hi):
                raise ParameterError(f"clearance {name} must be a number in {lo:g}..{hi:g} "
                                     f"NM, got {value!r}")

    @property
    def free_radius_nm(self) -> float:
        """Radius [NM] round a span end within which only land counts."""
        return self.approach_nm + FREE_MARGIN_NM

    def without_narrows(self) -> ClearanceRule:
        """The rule as the user set it (no narrows found by a lane's repair)."""
        return dataclasses.replace(self, narrows=())

    def kernel_array(self, search: bool = True, level1_lat_deg: float = 90.0) -> np.ndarray:
        """The walk's rule array (`route._land_walk.clearance_walk`); `search`: tight water
        left to the search's intermediate coastline (False: measured, as the check does);
        `level1_lat_deg`: poleward of it level 0 alone decides (undecided there = too close)."""
        return np.array([self.open_sea_nm, self.approach_nm, self.approach_zone_nm,
                         self.free_radius_nm, EPS_NM, self.open_sea_nm + NARROW_MARGIN_NM,
                         TIGHT_ROOM_NM, 1.0 if search else 0.0, level1_lat_deg])

    @property
    def words(self) -> str:
        """The rule in words, as a plan states it."""
        tight = ("; water narrower than ~10 NM searched on GSHHG intermediate resolution, "
                 "threaded at full resolution by the final repair")
        if self.open_sea_nm == 0.0 and self.approach_nm == 0.0:
            return "no clearance (off land only)" + tight
        return (f"clearance {self.open_sea_nm:g} NM open sea / {self.approach_nm:g} NM within "
                f"{self.approach_zone_nm:g} NM of the span ends and in narrow water (room within "
                f"10 NM < {self.open_sea_nm + NARROW_MARGIN_NM:g} NM)" + tight)


DEFAULT_CLEARANCE = ClearanceRule()  # the defaults of the CLI, the node and PlanOptions


def needed_clearance_nm(rule: ClearanceRule, end_nm: np.ndarray, room_nm: np.ndarray,
                        search: bool = True) -> np.ndarray:
    """The clearance [NM] points need under `rule` (the walk's, point by point): by their
    distance to the nearer span end `end_nm` and the room of their water `room_nm`; 0 in
    tight water when `search` (the search keeps off land there, the check measures it)."""
    end = np.asarray(end_nm, dtype=float)
    room = np.asarray(room_nm, dtype=float)
    need = np.where(end <= rule.free_radius_nm, 0.0,
                    np.where(end <= rule.approach_zone_nm, rule.approach_nm, rule.open_sea_nm))
    need = np.where(room < rule.open_sea_nm + NARROW_MARGIN_NM,
                    np.minimum(need, rule.approach_nm), need)
    return np.where(search & (room < TIGHT_ROOM_NM), 0.0, need)
