"""Environment along legs as broadcastable arrays (SI, directions in degrees true)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, fields

import numpy as np

G_M_S2 = 9.80665
_PM_HS_COEF = 0.21  # fully developed Pierson-Moskowitz sea: Hs = 0.21 U^2 / g


@dataclass(frozen=True)
class SeaState:
    """Wind (vector, where the air goes), wind sea, swell (coming from) and current (going to)."""

    wind_u_m_s: np.ndarray
    wind_v_m_s: np.ndarray
    wind_wave_hs_m: np.ndarray
    wind_wave_from_deg: np.ndarray
    wind_wave_period_s: np.ndarray
    swell_hs_m: np.ndarray
    swell_from_deg: np.ndarray
    swell_period_s: np.ndarray
    current_u_m_s: np.ndarray
    current_v_m_s: np.ndarray

    @classmethod
    def calm(cls, shape: tuple[int, ...] | int = ()) -> SeaState:
        """No wind, no waves, no current (periods set to a harmless 8 s)."""
        z = np.zeros(shape)
        p = np.full(shape, 8.0)
        return cls(z, z, z, z, p, z, z, p, z, z)

    @classmethod
    def from_arrays(cls, **kw: object) -> SeaState:
        """Build from keyword arrays; missing fields are calm; NaN becomes calm."""
        names = [f.name for f in fields(cls)]
        unknown = set(kw) - set(names)
        if unknown:
            raise TypeError(f"unknown SeaState fields: {sorted(unknown)}")
        arrays = [np.asarray(kw[n], dtype=float) for n in names if n in kw]
        shape = np.broadcast_shapes(*(a.shape for a in arrays)) if arrays else ()
        calm = cls.calm(shape)
        vals = {}
        for n in names:
            a = np.asarray(kw.get(n, getattr(calm, n)), dtype=float)
            default = 8.0 if n.endswith("period_s") else 0.0
            vals[n] = np.where(np.isfinite(a), a, default)
        return cls(**vals)

    @classmethod
    def from_forecast(cls, sample: Mapping[str, np.ndarray]) -> SeaState:
        """Build from ``ForecastSampler.sample`` output (CF names; NaN -> calm).

        Where the wind-sea/swell partition is missing (variable absent or NaN) the total
        sea fills it: if one part is known, the other is the energy remainder of the total
        (total direction and period); if neither is, the wind sea is the part a fully
        developed sea of the local wind explains (Hs <= 0.21 U^2/g, from the wind
        direction) and the remainder is swell from the mean wave direction.
        """
        shape = np.broadcast_shapes(*(np.shape(a) for a in sample.values()))

        def get(name: str, default: float = np.nan) -> np.ndarray:
            a = sample.get(name)
            a = np.full(shape, default) if a is None else np.asarray(a, dtype=float)
            return a if a.shape == shape else np.broadcast_to(a, shape)  # ~10 us a view

        u = _nz(get("eastward_wind"))
        v = _nz(get("northward_wind"))
        tot_hs = _nz(get("sea_surface_wave_significant_height"))
        tot_dir = _nz(get("sea_surface_wave_from_direction"))
        tot_t = _nz(get("sea_surface_wave_mean_period"), 8.0)
        ws = get("sea_surface_wind_wave_significant_height")
        sw = get("sea_surface_swell_wave_significant_height")
        ws_dir = get("sea_surface_wind_wave_from_direction")
        sw_dir = get("sea_surface_swell_wave_from_direction")
        ws_t = get("sea_surface_wind_wave_mean_period")
        sw_t = get("sea_surface_swell_wave_mean_period")
        has_ws, has_sw = np.isfinite(ws), np.isfinite(sw)
        wind_speed = np.hypot(u, v)
        wind_from = np.degrees(np.arctan2(-u, -v)) % 360.0
        pm_ws = np.minimum(tot_hs, _PM_HS_COEF * wind_speed**2 / G_M_S2)

        def rest(part: np.ndarray) -> np.ndarray:
            return np.sqrt(np.maximum(tot_hs**2 - np.where(np.isfinite(part), part, 0.0) ** 2, 0))

        ws_hs = np.where(has_ws, ws, np.where(has_sw, rest(sw), pm_ws))
        sw_hs = np.where(has_sw, sw, rest(ws_hs))
        ws_from = np.where(
            has_ws & np.isfinite(ws_dir), ws_dir,
            np.where(has_sw | (wind_speed <= 0.5), tot_dir, wind_from),
        )
        return cls.from_arrays(
            wind_u_m_s=u, wind_v_m_s=v,
            wind_wave_hs_m=ws_hs, wind_wave_from_deg=ws_from,
            wind_wave_period_s=np.where(has_ws & np.isfinite(ws_t), ws_t, tot_t),
            swell_hs_m=sw_hs,
            swell_from_deg=np.where(has_sw & np.isfinite(sw_dir), sw_dir, tot_dir),
            swell_period_s=np.where(has_sw & np.isfinite(sw_t), sw_t, tot_t),
            current_u_m_s=_nz(get("eastward_sea_water_velocity")),
            current_v_m_s=_nz(get("northward_sea_water_velocity")),
        )

    def take(self, index: np.ndarray) -> SeaState:
        """The sea states at `index` of the (flattened) points, e.g. each point repeated."""
        return SeaState(*(np.ravel(getattr(self, f.name))[index] for f in fields(self)))

    @property
    def wind_speed_m_s(self) -> np.ndarray:
        """True wind speed."""
        return np.hypot(self.wind_u_m_s, self.wind_v_m_s)

    @property
    def hs_m(self) -> np.ndarray:
        """Total significant wave height (energy sum of wind sea and swell)."""
        return np.hypot(self.wind_wave_hs_m, self.swell_hs_m)

    def broadcast(self, shape: tuple[int, ...]) -> SeaState:
        """All fields broadcast to ``shape`` (views)."""
        return SeaState(
            **{f.name: np.broadcast_to(getattr(self, f.name), shape) for f in fields(self)}
        )

    def shape(self) -> tuple[int, ...]:
        """Common broadcast shape of the fields."""
        return np.broadcast_shapes(*(np.shape(getattr(self, f.name)) for f in fields(self)))


def _nz(a: np.ndarray | None, default: float = 0.0) -> np.ndarray:
    if a is None:
        return np.asarray(default)
    return np.where(np.isfinite(a), a, default)
