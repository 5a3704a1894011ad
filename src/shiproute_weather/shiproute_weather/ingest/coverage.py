"""How much of a voyage a forecast covers in time, and what is used beyond it.

Inside the forecast's valid-time range its fields are interpolated. Beyond the last valid
time (or before the first) the edge field is held (persistence) for at most `persistence_h`,
and after that a monthly climatology when one is given (a canonical file whose valid times
name the months: `climatology_slices`), else calm water (no wind, waves or currents: missing
values, which the ship model takes as calm). A voyage that does not overlap the forecast at
all is refused.
`bounded_in_time` builds a sampler that does exactly this (the bare sampler clamps times to
its ends without limit); `time_coverage` states it in hours.
"""

from __future__ import annotations

from dataclasses import dataclass
from datetime import UTC, datetime
from typing import TYPE_CHECKING

import numpy as np
from shiproute_core.units import S_PER_DAY, S_PER_HOUR

from ..errors import ForecastCoverageError
from ..sampling.sampler import ForecastSampler

if TYPE_CHECKING:  # xarray is needed only with a climatology (~40 MB of imports otherwise)
    import xarray as xr

#: default persistence beyond the forecast's ends [h]: a day, after which a held field says
#: little more than climatology
PERSISTENCE_H = 24.0
#: the persisted edge field changes to calm over this span [s] (the interpolation takes the
#: nearer of the two within it)
_STEP_S = 1.0


def _iso(t_s: float) -> str:
    return datetime.fromtimestamp(t_s, UTC).strftime("%Y-%m-%dT%H:%MZ")


@dataclass(frozen=True)
class TimeCoverage:
    """Hours of a voyage [start, end] under the forecast, persistence and calm."""

    forecast_start_s: float
    forecast_end_s: float
    voyage_start_s: float
    voyage_end_s: float
    persistence_limit_h: float
    forecast_h: float
    persistence_h: float
    calm_h: float  # beyond persistence: climatology when `climatology` names one, else calm
    climatology: str = ""

    @property
    def voyage_h(self) -> float:
        return max(self.voyage_end_s - self.voyage_start_s, 0.0) / S_PER_HOUR

    @property
    def covered_pct(self) -> float:
        return 100.0 * self.forecast_h / self.voyage_h if self.voyage_h > 0 else 100.0

    def statements(self) -> list[str]:
        """What the voyage met beyond the forecast, in words (empty when fully covered)."""
        if self.forecast_h >= self.voyage_h - 1e-6:
            return []
        out = [f"forecast ({_iso(self.forecast_start_s)} .. {_iso(self.forecast_end_s)}) covers "
               f"{self.forecast_h:.1f} h of the {self.voyage_h:.1f} h voyage "
               f"({self.covered_pct:.0f} %)"]
        if self.persistence_h > 0:
            limit = (f"at most {self.persistence_limit_h:g} h"
                     if np.isfinite(self.persistence_limit_h) else "unbounded")
            out.append(f"forecast edge held (persistence, {limit}) for "
                       f"{self.persistence_h:.1f} h")
        if self.calm_h > 0 and self.climatology:
            out.append(f"monthly climatology ({self.climatology}) used for {self.calm_h:.1f} h "
                       "beyond the forecast and its persistence")
        elif self.calm_h > 0:
            out.append(f"calm water assumed for {self.calm_h:.1f} h beyond the forecast and "
                       "its persistence (no wind, waves or currents known)")
        return out


def _overlap_h(a0: float, a1: float, b0: float, b1: float) -> float:
    return max(min(a1, b1) - max(a0, b0), 0.0) / S_PER_HOUR


def time_coverage(times_s: np.ndarray, start_s: float, end_s: float,
                  persistence_h: float = PERSISTENCE_H, climatology: str = "") -> TimeCoverage:
    """Split the voyage [start_s, end_s] into forecast, persistence and calm hours."""
    t0, t1 = float(times_s[0]), float(times_s[-1])
    p = persistence_h * S_PER_HOUR
    fc = _overlap_h(start_s, end_s, t0, t1)
    pers = _overlap_h(start_s, end_s, t1, t1 + p) + _overlap_h(start_s, end_s, t0 - p, t0)
    total = max(end_s - start_s, 0.0) / S_PER_HOUR
    return TimeCoverage(t0, t1, start_s, end_s, persistence_h, fc, pers,
                        max(total - fc - pers, 0.0), climatology)


def require_overlap(times_s: np.ndarray, start_s: float, end_s: float, where: str) -> None:
    """Refuse a forecast whose valid times do not meet the voyage [start_s, end_s]."""
    t0, t1 = float(times_s[0]), float(times_s[-1])
    if end_s < t0 or start_s > t1:
        raise ForecastCoverageError(
            f"{where}: forecast valid {_iso(t0)} .. {_iso(t1)} does not overlap the voyage "
            f"{_iso(start_s)} .. {_iso(end_s)}; use a forecast for the voyage's dates")


def climatology_slices(sampler: ForecastSampler, clim: xr.Dataset, start_s: float,
                       until_s: float) -> tuple[list[np.ndarray], list[float]]:
    """Slices of a monthly climatology on the sampler's grid and channels: one at `start_s`
    (its month) and one at the middle of every later month up to past `until_s`. A field the
    climatology lacks is missing (calm); a month it lacks is refused."""
    from ..sampling.sampler import pack_fields
    from .regrid import regrid

    months = {int(str(t)[5:7]): k for k, t in enumerate(clim["time"].values.astype(
        "datetime64[M]"))}
    g = sampler.grid
    stamps = [start_s]
    d = datetime.fromtimestamp(start_s, UTC).replace(day=15, hour=0, minute=0, second=0,
                                                     microsecond=0)
    while True:
        d = (d.replace(month=d.month + 1) if d.month < 12
             else d.replace(year=d.year + 1, month=1))
        if d.timestamp() > start_s:
            stamps.append(d.timestamp())
        if d.timestamp() > until_s:
            break
    slices = []
    for ts in stamps:
        month = datetime.fromtimestamp(ts, UTC).month
        if month not in months:
            raise ForecastCoverageError(f"climatology has no values for month {month} "
                                        f"(months {sorted(months)})")
        one = clim.isel(time=[months[month]])
        on = regrid(one, g.latitudes_deg, g.longitudes_deg, one["time"].values)
        out = np.empty((1, g.n_lat, g.n_lon, sampler._data.shape[3]), dtype=sampler.dtype)
        nan = np.full((g.n_lat, g.n_lon), np.nan, dtype=np.float32)
        def month_values(n: str, on: xr.Dataset = on, nan: np.ndarray = nan) -> np.ndarray:
            return on[n].values[0] if n in on else nan

        pack_fields(out, sampler.variables, month_values)
        slices.append(out)
    return slices, stamps


def bounded_in_time(sampler: ForecastSampler, persistence_h: float = PERSISTENCE_H,
                    climatology: xr.Dataset | None = None,
                    until_s: float | None = None) -> ForecastSampler:
    """Sampler that holds the edge fields for `persistence_h` beyond the forecast's first and
    last valid times, then gives a monthly `climatology` (up to `until_s`) or missing values
    (calm), instead of clamping without limit.

    Two slices are added at each end (a copy of the edge slice and a missing one), plus the
    climatology's; the field array is copied once.
    """
    data = sampler._data
    t = sampler.times_s
    p = max(persistence_h, 0.0) * S_PER_HOUR
    nan = np.full((1, *data.shape[1:]), np.nan, dtype=data.dtype)
    head, tail = [nan], [nan]
    head_t, tail_t = [t[0] - p - _STEP_S], [t[-1] + p + _STEP_S]
    if climatology is not None:
        end = max(until_s if until_s is not None else t[-1], t[-1] + p) + 31 * S_PER_DAY
        tail, tail_t = climatology_slices(sampler, climatology, t[-1] + p + _STEP_S, end)
    if p > 0:
        head.append(data[:1])
        head_t.append(t[0] - p)
        tail.insert(0, data[-1:])
        tail_t.insert(0, t[-1] + p)
    out = ForecastSampler.from_packed(np.concatenate([*head, data, *tail]),
                                      np.concatenate([head_t, t, tail_t]), sampler.grid,
                                      sampler.variables)
    out.record = sampler.record
    out.forecast_times_s = t
    return out


def load_climatology(path: str) -> xr.Dataset:
    """A monthly climatology file as a canonical dataset (one valid time per month of any
    year; nothing is estimated: a field it lacks stays calm)."""
    from ..contract.validate import validate
    from .loaders import open_file

    ds = validate(open_file(path), path)
    months = ds["time"].values.astype("datetime64[M]").astype(int) % 12
    if np.unique(months).size != months.size:
        raise ForecastCoverageError(f"{path}: a climatology needs one valid time per month; "
                                    f"got {months.size} times in {np.unique(months).size} "
                                    "months")
    return ds
