"""Forecast slices thinned for the page: Hs as a coarse colour grid, wind as barb positions.

The planner's slices (0.5 deg, ~100 x 260 cells, 13 fields) are far more than a chart shows.
For each slice the display keeps the total significant wave height on a grid of at most
`max_cells` cells (each cell the highest Hs of the source cells it covers, so thinning never
hides a peak), coded as 0.1 m steps in one byte, and the 10 m wind vector every
`barb_spacing_deg`. A cycle of 129 slices then holds ~1 MB instead of ~90 MB.
"""

from __future__ import annotations

import base64
import json
import math
import warnings
from dataclasses import dataclass

import numpy as np

from .errors import MalformedMessageError

HS_NAME = "sea_surface_wave_significant_height"
WIND_U_NAME = "eastward_wind"
WIND_V_NAME = "northward_wind"
HS_STEP_M = 0.1  #: Hs code step [m]; code 255 = no value
HS_MISSING = 255


@dataclass(frozen=True)
class GridSpec:
    """A regular lat/lon grid: origin, spacing, shape (row-major, latitude rows)."""

    lat0_deg: float
    dlat_deg: float
    n_lat: int
    lon0_deg: float
    dlon_deg: float
    n_lon: int


@dataclass(frozen=True)
class SliceView:
    """One valid time, thinned for the page."""

    index: int
    valid_s: float
    hs_grid: GridSpec
    hs_codes: bytes  # n_lat * n_lon bytes, HS_STEP_M per code, HS_MISSING = no value
    wind: tuple[float, ...]  # flat lon_deg, lat_deg, u_m_s, v_m_s, ...
    member: int = 0  # ensemble member of the slice; -1 = combined over the members

    def to_json(self) -> bytes:
        """Body of `/api/forecast/<index>`."""
        g = self.hs_grid
        return json.dumps({
            "index": self.index, "valid_s": self.valid_s, "member": self.member,
            "grid": [g.lat0_deg, g.dlat_deg, g.n_lat, g.lon0_deg, g.dlon_deg, g.n_lon],
            "hs_step_m": HS_STEP_M, "hs_missing": HS_MISSING,
            "hs_b64": base64.b64encode(self.hs_codes).decode(),
            "wind": list(self.wind),
        }, separators=(",", ":")).encode()


def _block_max(values: np.ndarray, stride: int) -> np.ndarray:
    n_lat, n_lon = values.shape
    pad_lat, pad_lon = (-n_lat) % stride, (-n_lon) % stride
    v = np.pad(values, ((0, pad_lat), (0, pad_lon)), constant_values=np.nan)
    v = v.reshape(v.shape[0] // stride, stride, v.shape[1] // stride, stride)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # all-NaN blocks (land) stay NaN
        return np.nanmax(v, axis=(1, 3))


def thin_slice(index: int, valid_s: float, grid: GridSpec, fields: dict[str, np.ndarray],
               max_cells: int = 8000, barb_spacing_deg: float = 2.5, member: int = 0
               ) -> SliceView:
    """Thin one decoded slice (flat float32 arrays keyed by CF name) for the page."""
    n = grid.n_lat * grid.n_lon
    if grid.n_lat < 1 or grid.n_lon < 1 or not (grid.dlat_deg > 0 and grid.dlon_deg > 0):
        raise MalformedMessageError(f"forecast slice {index}: grid {grid} is not a regular grid")
    for name, arr in fields.items():
        if arr.size != n:
            raise MalformedMessageError(
                f"forecast slice {index}: field {name} has {arr.size} values, expected "
                f"{grid.n_lat} x {grid.n_lon}")
    hs = fields.get(HS_NAME)
    if hs is None:
        hs = np.full(n, np.nan, dtype=np.float32)
    stride = max(1, math.ceil(math.sqrt(n / max_cells)))
    hs_thin = _block_max(hs.reshape(grid.n_lat, grid.n_lon).astype(np.float32), stride)
    codes = np.where(np.isfinite(hs_thin),
                     np.clip(np.round(np.nan_to_num(hs_thin) / HS_STEP_M), 0, HS_MISSING - 1),
                     HS_MISSING).astype(np.uint8)
    hs_grid = GridSpec(grid.lat0_deg + (stride - 1) * grid.dlat_deg / 2, grid.dlat_deg * stride,
                       hs_thin.shape[0], grid.lon0_deg + (stride - 1) * grid.dlon_deg / 2,
                       grid.dlon_deg * stride, hs_thin.shape[1])
    wind: list[float] = []
    u, v = fields.get(WIND_U_NAME), fields.get(WIND_V_NAME)
    if u is not None and v is not None:
        s_lat = max(1, round(barb_spacing_deg / grid.dlat_deg))
        s_lon = max(1, round(barb_spacing_deg / grid.dlon_deg))
        u2 = u.reshape(grid.n_lat, grid.n_lon)[::s_lat, ::s_lon]
        v2 = v.reshape(grid.n_lat, grid.n_lon)[::s_lat, ::s_lon]
        lat = grid.lat0_deg + np.arange(0, grid.n_lat, s_lat) * grid.dlat_deg
        lon = grid.lon0_deg + np.arange(0, grid.n_lon, s_lon) * grid.dlon_deg
        lon_g, lat_g = np.meshgrid(lon, lat)
        ok = np.isfinite(u2) & np.isfinite(v2)
        flat = np.stack([lon_g[ok], lat_g[ok], u2[ok], v2[ok]], axis=1)
        wind = np.round(flat.astype(np.float64), 2).ravel().tolist()
    return SliceView(index, float(valid_s), hs_grid, codes.tobytes(), tuple(wind), member)
