"""What the route model needs of a weather forecast: its fields at points in space and time."""

from __future__ import annotations

from typing import Protocol

import numpy as np


class ForecastSource(Protocol):
    """A forecast the route model samples: `shiproute_weather`'s `ForecastSampler` and the
    time-bounded samplers made from it (`coverage.bounded_in_time`)."""

    def sample(self, lon_deg: np.ndarray, lat_deg: np.ndarray,
               time_s: np.ndarray) -> dict[str, np.ndarray]:
        """Every field at the points (arrays broadcast to one shape), keyed by CF name, SI."""
        ...
