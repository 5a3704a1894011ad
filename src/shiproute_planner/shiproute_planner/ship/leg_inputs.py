"""The per-leg inputs of the compiled ship kernels as fixed-length, typed tuples."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from .seastate import SeaState

FloatArray = npt.NDArray[np.float64]

# (par, tables): the fast model's kernel parameters and its nine tables, in kernel order
# (calm resistance, wake, wind-sea and swell added resistance, wind-sea and swell motion,
# wind coefficient, SFOC grid, SFOC on the grid)
KernelTables = tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray, FloatArray,
                     FloatArray, FloatArray, FloatArray]


class LegInputs(NamedTuple):
    """One leg per element, broadcast to one shape and flattened (SI; degrees, going to /
    coming from as in `SeaState`); `drive` is the engine RPM or the speed through water."""

    drive: FloatArray
    heading_deg: FloatArray
    wind_u_m_s: FloatArray
    wind_v_m_s: FloatArray
    wind_wave_hs_m: FloatArray
    wind_wave_from_deg: FloatArray
    wind_wave_period_s: FloatArray
    swell_hs_m: FloatArray
    swell_from_deg: FloatArray
    swell_period_s: FloatArray
    current_u_m_s: FloatArray
    current_v_m_s: FloatArray


def leg_inputs(drive: npt.ArrayLike, heading_deg: npt.ArrayLike, sea: SeaState,
               currents: bool = True) -> tuple[LegInputs, tuple[int, ...]]:
    """The flattened inputs and the broadcast shape they came from; without `currents` the
    current fields are zero and take no part in the shape (for kernels that ignore them)."""
    current_u, current_v = (sea.current_u_m_s, sea.current_v_m_s) if currents else (0.0, 0.0)
    fields = (
        drive, heading_deg, sea.wind_u_m_s, sea.wind_v_m_s, sea.wind_wave_hs_m,
        sea.wind_wave_from_deg, sea.wind_wave_period_s, sea.swell_hs_m, sea.swell_from_deg,
        sea.swell_period_s, current_u, current_v,
    )
    arrays = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in fields))
    flat = LegInputs._make(np.ascontiguousarray(a).reshape(-1) for a in arrays)
    return flat, arrays[0].shape
