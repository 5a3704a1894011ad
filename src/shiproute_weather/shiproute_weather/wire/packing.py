"""16-bit simple packing of a float32 field for the wire (GRIB2 template 5.0, CF scale/offset).

value = float32(add_offset + scale_factor * code), computed in float64; code 65535 = missing
(NaN). `pack_field` chooses add_offset = min and scale_factor = (max - min) / 65534 over the
finite values and rounds to the nearest code, so a decoded value is within scale_factor / 2
of the original (plus one float32 rounding). The forecast sources are themselves packed at
12-16 bits and the planner stores half precision, so this loses nothing the consumers keep,
at half the bytes of float32. Plain numpy: the weather node encodes a whole cycle before
announcing it and stays free of compiled kernels (their resident memory); the planner decodes
inside its own compiled packing kernel (`sampling.pack_kernel`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import PackingError, SliceError

MISSING_CODE = 65535  #: packed value of a missing (NaN) value
MAX_CODE = 65534  #: largest packed value of a real value: codes 0..65534 span min..max


@dataclass(frozen=True)
class PackedField:
    """A field in simple packing: codes (uint16, flat), and the decoding constants."""

    codes: np.ndarray
    add_offset: float
    scale_factor: float

    @property
    def size(self) -> int:
        """Number of values."""
        return int(self.codes.size)

    @property
    def nbytes(self) -> int:
        """Bytes of the codes."""
        return int(self.codes.nbytes)


def pack_field(values: np.ndarray, name: str = "field") -> PackedField:
    """Simple packing of float32 values (any shape, packed flat in C order).

    Raises `PackingError` for +-inf (a value no 16-bit code can represent); callers send such
    a field as float32 instead.
    """
    flat = np.ascontiguousarray(values, dtype=np.float32).reshape(-1)
    lo, hi = float(np.fmin.reduce(flat)), float(np.fmax.reduce(flat))  # NaN skipped
    if math.isnan(lo):  # every value missing
        return PackedField(np.full(flat.size, MISSING_CODE, dtype=np.uint16), 0.0, 0.0)
    if math.isinf(lo) or math.isinf(hi):
        raise PackingError(name, "holds +-inf, which 16-bit simple packing cannot represent")
    scale = (hi - lo) / MAX_CODE
    inv_scale = 1.0 / scale if scale > 0.0 else 0.0
    # t = (v - lo) / scale + 0.5 in float64 lies in [0.5, 65534.5] (up to rounding), so the
    # truncation is round-half-up and never leaves 0..65534; NaN is cast after the codes
    t = flat.astype(np.float64)
    t *= inv_scale
    t += 0.5 - lo * inv_scale
    missing = np.isnan(t)
    t[missing] = 0.0
    codes = t.astype(np.uint16)
    codes[missing] = MISSING_CODE
    return PackedField(codes, lo, scale)


def unpack_field(packed: PackedField, out: np.ndarray | None = None) -> np.ndarray:
    """Decoded float32 values of a packed field (flat), written into `out` when given."""
    codes = np.ascontiguousarray(packed.codes, dtype=np.uint16).reshape(-1)
    if out is None:
        out = np.empty(codes.size, dtype=np.float32)
    elif out.shape != codes.shape or out.dtype != np.float32:
        raise ValueError(f"output array {out.dtype}{out.shape} does not fit {codes.size} "
                         "float32 values")
    values = float(packed.add_offset) + float(packed.scale_factor) * codes.astype(np.float64)
    out[...] = values  # float64 -> float32: one rounding, as `sampling.pack_kernel.decode`
    out[codes == MISSING_CODE] = np.nan
    return out


def field_values(f: Any) -> np.ndarray | PackedField:
    """The values of a ForecastField message (or any object with its `name`, `data`, `packed`,
    `add_offset`, `scale_factor`) without copying: a float32 view of `data`, or the packed codes
    (a uint16 view of `packed`) with their scaling. ROS-free and light, so the planner node
    reads slices without importing the weather package's xarray side. Raises SliceError when
    both hold values."""
    if len(f.packed) and len(f.data):
        raise SliceError(f"field {f.name}: both data ({len(f.data)}) and packed "
                         f"({len(f.packed)}) hold values; exactly one may")
    if len(f.packed):
        return PackedField(np.frombuffer(f.packed, dtype=np.uint16), float(f.add_offset),
                           float(f.scale_factor))
    return np.frombuffer(f.data, dtype=np.float32)
