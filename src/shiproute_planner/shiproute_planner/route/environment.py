"""The environment a route meets: forecast sampler (or calm water) + ship performance model."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numba
import numpy as np
from shiproute_core.geodesy import wrap_lon

from .forecast_source import ForecastSource
from .risk import RiskSpec

if TYPE_CHECKING:
    from ..ship import LegPerformance, PerformanceModel, SeaState

# LegPerformance fields the evaluator keeps per leg (ship-model contract in ARCHITECTURE.md).
PERF_FIELDS = (
    "stw_m_s", "sog_m_s", "cog_deg", "brake_power_kw", "fuel_t_per_h", "engine_load",
    "engine_limit_exceeded", "p_slamming", "p_deck_wetness", "p_propeller_emergence",
    "surf_riding", "parametric_roll", "synchronous_roll", "high_wave_group", "hs_m",
    "wind_speed_m_s",
)


_PERIOD_KEYS = (
    "sea_surface_wave_mean_period",
    "sea_surface_wind_wave_mean_period",
    "sea_surface_swell_wave_mean_period",
)


@dataclass(frozen=True)
class Environment:
    """Weather `sampler` (None = calm water everywhere) and a ship `model`.

    `sampler.sample(lon, lat, t_s)` follows the shiproute_weather contract; `model.evaluate`
    follows the PerformanceModel contract of `shiproute_planner.ship`.
    """

    model: PerformanceModel
    sampler: ForecastSource | None = None
    cycle_id: str = ""
    #: `route.risk.RiskSpec` to plan on every ensemble member of the sampler (None: plan on
    #: its one forecast, the members' mean for an ensemble)
    risk: RiskSpec | None = None

    def sea_state(self, lon_deg: np.ndarray, lat_deg: np.ndarray,
                  time_s: np.ndarray) -> SeaState:
        """SeaState at the points (longitudes in any frame)."""
        from ..ship import SeaState

        if self.sampler is None:
            return SeaState.calm(np.shape(lon_deg))
        sample = self._sample(lon_deg, lat_deg, time_s)
        for key in _PERIOD_KEYS:
            if key in sample:
                # the ship model accepts 0.5..30 s; interpolated young wind seas can be shorter
                sample[key] = np.clip(sample[key], 0.5, 30.0)
        return SeaState.from_forecast(sample)

    def weather(self, lon_deg: np.ndarray, lat_deg: np.ndarray,
                time_s: np.ndarray) -> dict[str, np.ndarray]:
        """Raw forecast sample (for reporting wave/wind directions); empty in calm water."""
        if self.sampler is None:
            return {}
        return self._sample(lon_deg, lat_deg, time_s)

    def _sample(self, lon_deg: np.ndarray, lat_deg: np.ndarray,
                time_s: np.ndarray) -> dict[str, np.ndarray]:
        """Sample on one thread: populations are a few hundred points, where a parallel
        kernel spends more time waking threads (and far more on a busy machine) than working."""
        assert self.sampler is not None, "callers sample only with a forecast"
        prev = numba.get_num_threads()
        numba.set_num_threads(1)
        try:
            return self.sampler.sample(wrap_lon(lon_deg), lat_deg, time_s)
        finally:
            numba.set_num_threads(prev)

    def perform(self, rpm: np.ndarray, heading_deg: np.ndarray,
                sea: SeaState) -> LegPerformance:
        """LegPerformance of the ship model."""
        return self.model.evaluate(rpm, heading_deg, sea)
