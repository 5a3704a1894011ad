"""Read-only view of a `ForecastSampler`'s packed field array for compiled route kernels.

The planner's population evaluator calls the sampler's own trilinear kernel stage by stage
without going through `sample` (which builds a dict of float64 arrays per call); this module
hands it the arrays and the channel layout that `sample` uses internally.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..contract.canonical import DIRECTION_VARIABLES
from .sampler import ForecastSampler


@dataclass(frozen=True)
class SamplerArrays:
    """Arguments of `sampling.interp_kernel.trilinear` and where each variable's channel sits.

    `channels[name]` is the channel index of a scalar variable, or of the sine channel of a
    direction variable (its cosine follows at index + 1).
    """

    data: np.ndarray  # (time, lat, lon, channel) float32, or uint16 binary16 bits
    times_s: np.ndarray
    lat0_deg: float
    dlat_deg: float
    lon0_deg: float
    dlon_deg: float
    periodic: bool
    channels: dict[str, int]
    directions: frozenset[str]


def sampler_arrays(sampler: ForecastSampler) -> SamplerArrays:
    """The packed arrays of `sampler` (no copy; half-precision storage as its uint16 bits,
    which `sampling.interp_kernel.trilinear` reads)."""
    channels: dict[str, int] = {}
    c = 0
    for name in sampler.variables:
        channels[name] = c
        c += 2 if name in DIRECTION_VARIABLES else 1
    g = sampler.grid
    return SamplerArrays(sampler.kernel_data, sampler.times_s, float(g.lat0_deg),
                         float(g.dlat_deg), float(g.lon0_deg), float(g.dlon_deg),
                         bool(g.is_global_in_lon), channels, frozenset(DIRECTION_VARIABLES))
