"""The latitude bound of a voyage: the route limits' default (70 degrees) keeps searches out
of polar water, but a voyage whose sea lane itself runs beyond it (round the North Cape to
Murmansk, to Hammerfest) would be infeasible from the start; there the bound follows the
lane with a margin and the plan says so."""

from __future__ import annotations

import dataclasses
import itertools
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..geo.sea_lanes import sea_lane_between
from ..route.problem import RouteLimits

LANE_MARGIN_DEG = 1.0  # room beyond the lane's highest latitude for the search (~60 NM)
MAX_BOUND_DEG = 85.0  # never beyond: the search's spherical steps and rasters stop near here


def lane_max_abs_lat_deg(ports: Sequence[Any]) -> float:
    """Highest |latitude| of the ports and of the sea lanes between consecutive ones [deg]."""
    top = max(abs(float(p.lat_deg)) for p in ports)
    for a, b in itertools.pairwise(ports):
        lane = sea_lane_between(a.lon_deg, a.lat_deg, b.lon_deg, b.lat_deg)
        if lane is not None and len(lane):
            top = max(top, float(np.max(np.abs(lane[:, 1]))))
    return top


def voyage_lat_bound(limits: RouteLimits, ports: Sequence[Any],
                     fixed: bool = False) -> tuple[RouteLimits, list[str]]:
    """`limits` with the latitude bound raised to the voyage's sea lane plus a margin where the
    lane runs beyond it (not when the user `fixed` the bound); notes for the plan."""
    need = lane_max_abs_lat_deg(ports) + LANE_MARGIN_DEG
    if fixed or need <= limits.lat_bound_deg:
        return limits, []
    bound = min(need, MAX_BOUND_DEG)
    note = (f"latitude bound raised from {limits.lat_bound_deg:g} to {bound:.1f} degrees for "
            f"this voyage: its sea lane reaches {need - LANE_MARGIN_DEG:.1f} degrees; sea ice "
            "and icing are not checked (no ice data): check the ice chart")
    return dataclasses.replace(limits, lat_bound_deg=bound), [note]
