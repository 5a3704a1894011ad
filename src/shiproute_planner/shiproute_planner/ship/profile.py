"""Ship performance profile as a NetCDF table: export from any model, import as a model.

Layout (one file per ship and loading condition, CF-style attributes):
dims ``rpm`` (or ``stw_kn``), ``hs_m``, ``rel_wave_deg`` (0 = head seas), ``wind_speed_m_s``
(true), ``rel_wind_deg`` (true wind angle off the bow, 0 = head wind); variables
``brake_power_kw``, ``fuel_t_per_h`` and, on an RPM axis, ``stw_kn`` (on a speed axis,
``rpm``). Waves in the table are one wind-sea system with T01 = max(3.5, 3.86 sqrt(Hs)) s
(attribute ``wave_period_rule``). On import, wind sea and swell are merged into one
system: Hs = sqrt(Hs_ws^2 + Hs_sw^2) coming from the energy-weighted mean direction.
Seakeeping and currents are computed as in the physics model at the profile's speed.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from scipy.interpolate import RegularGridInterpolator
from shiproute_core.units import M_S_PER_KNOT

from .errors import ProfileError
from .performance import LegPerformance, PerformanceModel
from .physics import PhysicsModel, flatten_legs, flatten_sea, relative_wave_deg
from .seastate import SeaState
from .spec import ShipSpec
from .validate import check_inputs, check_range, check_sea

if TYPE_CHECKING:  # imported where a profile is read or written: ~50 MB resident with pandas
    import xarray as xr

WEATHER_DIMS = ("hs_m", "rel_wave_deg", "wind_speed_m_s", "rel_wind_deg")


def profile_wave_period_s(hs_m: np.ndarray) -> np.ndarray:
    """Mean wave period assumed by profile tables (ITTC open-ocean relation, floor 3.5 s)."""
    return np.maximum(3.5, 3.86 * np.sqrt(np.asarray(hs_m, dtype=float)))


@dataclass(frozen=True)
class ProfileGrid:
    """Axes of an exported profile."""

    rpm: tuple[float, ...]
    hs_m: tuple[float, ...] = (0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0)
    rel_wave_deg: tuple[float, ...] = (0.0, 30.0, 60.0, 90.0, 120.0, 150.0, 180.0)
    wind_speed_m_s: tuple[float, ...] = (0.0, 5.0, 10.0, 15.0, 20.0, 25.0, 30.0)
    rel_wind_deg: tuple[float, ...] = (0.0, 30.0, 60.0, 90.0, 120.0, 150.0, 180.0)

    @classmethod
    def for_ship(cls, ship: ShipSpec, n_rpm: int = 12) -> ProfileGrid:
        """Default grid: ``n_rpm`` RPMs from the engine's minimum to maximum."""
        e = ship.engine
        return cls(rpm=tuple(float(x) for x in np.linspace(e.rpm_min, e.rpm_max, n_rpm)))


def grid_sea(grid: ProfileGrid) -> tuple[np.ndarray, np.ndarray, SeaState]:
    """RPM, heading (0 = north) and sea state on the full 5-D grid (arrays of its shape)."""
    r, h, aw, w, awi = np.meshgrid(
        grid.rpm, grid.hs_m, grid.rel_wave_deg, grid.wind_speed_m_s, grid.rel_wind_deg,
        indexing="ij",
    )
    wind_from = np.radians(awi)  # heading 0: the wind comes from the relative angle
    sea = SeaState.from_arrays(
        wind_u_m_s=-w * np.sin(wind_from), wind_v_m_s=-w * np.cos(wind_from),
        wind_wave_hs_m=h, wind_wave_from_deg=aw, wind_wave_period_s=profile_wave_period_s(h),
    )
    return r, np.zeros_like(r), sea


def export_profile(model: PerformanceModel, path: str | Path, grid: ProfileGrid) -> xr.Dataset:
    """Evaluate ``model`` on ``grid`` and write the NetCDF profile to ``path``."""
    import xarray as xr

    rpm, hdg, sea = grid_sea(grid)
    res = model.evaluate(rpm, hdg, sea)
    dims = ("rpm", *WEATHER_DIMS)
    ds = xr.Dataset(
        {
            "brake_power_kw": (dims, res.brake_power_kw, {"units": "kW"}),
            "fuel_t_per_h": (dims, res.fuel_t_per_h, {"units": "t h-1"}),
            "stw_kn": (dims, res.stw_m_s / M_S_PER_KNOT, {"units": "knot"}),
        },
        coords={
            "rpm": ("rpm", np.asarray(grid.rpm), {"units": "min-1"}),
            "hs_m": ("hs_m", np.asarray(grid.hs_m), {"units": "m"}),
            "rel_wave_deg": ("rel_wave_deg", np.asarray(grid.rel_wave_deg), {"units": "degree"}),
            "wind_speed_m_s": ("wind_speed_m_s", np.asarray(grid.wind_speed_m_s),
                               {"units": "m s-1"}),
            "rel_wind_deg": ("rel_wind_deg", np.asarray(grid.rel_wind_deg), {"units": "degree"}),
        },
        attrs={
            "title": f"ship performance profile: {model.ship.name}",
            "ship": model.ship.name,
            "loading_condition": model.ship.condition.name,
            "wave_period_rule": "T01 = max(3.5, 3.86 sqrt(Hs)) s, one wind-sea system",
            "source_model": type(model).__name__,
        },
    )
    ds.to_netcdf(path)
    return ds


class ProfileModel:
    """A NetCDF performance profile read and interpolated (linear, clamped) as a ship model."""

    def __init__(self, ship: ShipSpec, path: str | Path) -> None:
        self.ship = ship
        self.physics = PhysicsModel(ship)
        try:
            import xarray as xr

            ds = xr.load_dataset(path)
        except (OSError, ValueError) as exc:
            raise ProfileError(f"{path}: cannot read NetCDF profile: {exc}") from exc
        made_for = str(ds.attrs.get("ship", "") or "")
        if made_for and made_for != ship.name:
            raise ProfileError(f"{path}: profile of ship '{made_for}', not of '{ship.name}' "
                               "(a model file for another ship)")
        self.condition = str(ds.attrs.get("loading_condition", "") or "")
        axis = "rpm" if "rpm" in ds.dims else "stw_kn" if "stw_kn" in ds.dims else None
        if axis is None:
            raise ProfileError(f"{path}: needs an 'rpm' or 'stw_kn' dimension")
        need = ["brake_power_kw", "fuel_t_per_h", "stw_kn" if axis == "rpm" else "rpm"]
        for name in (*WEATHER_DIMS, *need):
            if name not in ds:
                raise ProfileError(f"{path}: missing variable or dimension '{name}'")
        dims = (axis, *WEATHER_DIMS)
        self.axis = axis
        self._points = tuple(np.asarray(ds[d].values, dtype=float) for d in dims)
        for d, p in zip(dims, self._points, strict=True):
            if p.size < 2 or np.any(np.diff(p) <= 0):
                raise ProfileError(f"{path}: axis '{d}' must have >= 2 increasing values")
        self._tables = {
            k: np.asarray(ds[k].transpose(*dims).values, dtype=float) for k in need
        }

    def _interp(self, name: str, pts: np.ndarray) -> np.ndarray:
        clipped = np.stack(
            [np.clip(pts[:, i], p[0], p[-1]) for i, p in enumerate(self._points)], axis=-1
        )
        f = RegularGridInterpolator(self._points, self._tables[name], method="linear")
        return f(clipped)

    def _weather(self, hdg: np.ndarray, s: SeaState) -> np.ndarray:
        e_ws, e_sw = s.wind_wave_hs_m**2, s.swell_hs_m**2
        ang_ws, ang_sw = np.radians(s.wind_wave_from_deg), np.radians(s.swell_from_deg)
        x = e_ws * np.sin(ang_ws) + e_sw * np.sin(ang_sw)
        y = e_ws * np.cos(ang_ws) + e_sw * np.cos(ang_sw)
        wave_from = np.degrees(np.arctan2(x, y))
        wind_from = np.degrees(np.arctan2(-s.wind_u_m_s, -s.wind_v_m_s))
        return np.stack(
            [s.hs_m, relative_wave_deg(hdg, wave_from), s.wind_speed_m_s,
             relative_wave_deg(hdg, wind_from)], axis=-1,
        )

    def evaluate(self, rpm: np.ndarray, heading_deg: np.ndarray, sea: SeaState) -> LegPerformance:
        """Evaluate legs by interpolating the table (same contract as the physics model)."""
        rpm = np.asarray(rpm, dtype=float)
        heading_deg = np.asarray(heading_deg, dtype=float)
        check_inputs(self.ship, rpm, heading_deg, sea)
        shape, _, rpm1, hdg, s = flatten_legs(rpm, heading_deg, sea)
        weather = self._weather(hdg, s)
        if self.axis == "rpm":
            pts = np.column_stack([rpm1, weather])
            v = self._interp("stw_kn", pts) * M_S_PER_KNOT
        else:
            v = self._speed_from_rpm(rpm1, weather)
            pts = np.column_stack([v / M_S_PER_KNOT, weather])
        pb = self._interp("brake_power_kw", pts)
        out = self.physics.finish_legs(rpm1, hdg, s, v, pb)
        out["fuel_t_per_h"] = self._interp("fuel_t_per_h", pts)
        return LegPerformance(**{k: a.reshape(shape) for k, a in out.items()})

    def _speed_from_rpm(self, rpm: np.ndarray, weather: np.ndarray) -> np.ndarray:
        """Speed axis tables: invert rpm(speed) per leg (rpm increases with speed)."""
        speeds = self._points[0]
        n, m = rpm.size, speeds.size
        pts = np.column_stack([np.repeat(speeds[None, :], n, 0).reshape(-1),
                               np.repeat(weather, m, axis=0)])
        table_rpm = self._interp("rpm", pts).reshape(n, m)
        k = np.clip((table_rpm < rpm[:, None]).sum(axis=1), 1, m - 1)
        r0 = table_rpm[np.arange(n), k - 1]
        r1 = table_rpm[np.arange(n), k]
        f = np.clip((rpm - r0) / np.maximum(r1 - r0, 1e-9), 0.0, 1.0)
        return (speeds[k - 1] + f * (speeds[k] - speeds[k - 1])) * M_S_PER_KNOT

    def rpm_for_speed(
        self, stw_m_s: np.ndarray, heading_deg: np.ndarray, sea: SeaState
    ) -> np.ndarray:
        """RPM for a speed through water, by inverting the table's speed(rpm) per leg."""
        stw = np.asarray(stw_m_s, dtype=float)
        heading_deg = np.asarray(heading_deg, dtype=float)
        check_range("stw_m_s", stw, 0.05, 30.0)
        check_sea(sea)
        shape = np.broadcast_shapes(stw.shape, heading_deg.shape, sea.shape())
        n = int(np.prod(shape))
        v = np.broadcast_to(stw, shape).reshape(n)
        hdg = np.broadcast_to(heading_deg, shape).reshape(n)
        weather = self._weather(hdg, flatten_sea(sea, shape, n))
        if self.axis == "stw_kn":
            return self._interp("rpm", np.column_stack([v / M_S_PER_KNOT, weather])).reshape(shape)
        rpms = self._points[0]
        m = rpms.size
        pts = np.column_stack([np.repeat(rpms[None, :], n, 0).reshape(-1),
                               np.repeat(weather, m, axis=0)])
        table_v = self._interp("stw_kn", pts).reshape(n, m) * M_S_PER_KNOT
        k = np.clip((table_v < v[:, None]).sum(axis=1), 1, m - 1)
        v0, v1 = table_v[np.arange(n), k - 1], table_v[np.arange(n), k]
        f = (v - v0) / np.maximum(v1 - v0, 1e-9)
        return (rpms[k - 1] + f * (rpms[k] - rpms[k - 1])).reshape(shape)
