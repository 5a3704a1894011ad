"""16-bit simple packing of a float32 field for the wire (GRIB2 template 5.0, CF scale/offset).

value = float32(add_offset + scale_factor * code), computed in float64; code 65535 = missing
(NaN). `pack_field` chooses add_offset = min and scale_factor = (max - min) / 65534 over the
finite values and rounds to the nearest code, so a decoded value is within scale_factor / 2
of the original (plus one float32 rounding). The forecast sources are themselves packed at
12-16 bits and the planner stores half precision, so this loses nothing the consumers keep,
at half the bytes of float32. Numba kernels: one pass for the range, one to quantise.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from .errors import PackingError

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


@njit(cache=True, nogil=True, inline="always")
def _lower(a: float, lo: float) -> float:
    return a if a < lo else lo  # NaN compares false: skipped


@njit(cache=True, nogil=True, inline="always")
def _upper(a: float, hi: float) -> float:
    return a if a > hi else hi


@njit(cache=True, nogil=True)
def _value_range(values: np.ndarray) -> tuple[float, float]:
    """(min, max) of float32 values with NaN skipped (+inf, -inf when all are NaN). Four
    independent accumulators: the compare chains overlap (~3x a single running min/max)."""
    n = values.shape[0]
    l0 = l1 = l2 = l3 = np.float32(np.inf)
    h0 = h1 = h2 = h3 = np.float32(-np.inf)
    n4 = n - n % 4
    for i in range(0, n4, 4):
        a, b, c, d = values[i], values[i + 1], values[i + 2], values[i + 3]
        l0, h0 = _lower(a, l0), _upper(a, h0)
        l1, h1 = _lower(b, l1), _upper(b, h1)
        l2, h2 = _lower(c, l2), _upper(c, h2)
        l3, h3 = _lower(d, l3), _upper(d, h3)
    for i in range(n4, n):
        l0, h0 = _lower(values[i], l0), _upper(values[i], h0)
    return (float(min(min(l0, l1), min(l2, l3))), float(max(max(h0, h1), max(h2, h3))))


@njit(cache=True, nogil=True)
def _quantise(values: np.ndarray, offset: float, inv_scale: float, codes: np.ndarray) -> None:
    """codes[i] = nearest code of values[i], NaN -> MISSING_CODE (float64 arithmetic; with
    offset = min and inv_scale = 65534 / (max - min), t lies in [0.5, 65534.5] up to float64
    rounding, so the truncation is round-half-up and never leaves 0..65534)."""
    c0 = 0.5 - offset * inv_scale
    for i in range(values.shape[0]):
        v = values[i]
        q = np.uint16(np.int32(np.float64(v) * inv_scale + c0))
        codes[i] = q if v == v else np.uint16(65535)


@njit(cache=True, nogil=True, inline="always")
def decode(code: np.uint16, offset: float, scale: float) -> np.float32:
    """float32 value of a code: float32(offset + scale * code) in float64, 65535 -> NaN."""
    v = np.float32(offset + scale * np.float64(code))
    return np.float32(np.nan) if code == 65535 else v


@njit(cache=True, nogil=True)
def _dequantise(codes: np.ndarray, offset: float, scale: float, out: np.ndarray) -> None:
    for i in range(codes.shape[0]):
        out[i] = decode(codes[i], offset, scale)


def pack_field(values: np.ndarray, name: str = "field") -> PackedField:
    """Simple packing of float32 values (any shape, packed flat in C order).

    Raises `PackingError` for +-inf (a value no 16-bit code can represent); callers send such
    a field as float32 instead.
    """
    flat = np.ascontiguousarray(values, dtype=np.float32).reshape(-1)
    lo, hi = _value_range(flat)
    if math.isinf(lo) or math.isinf(hi):
        if lo <= hi:  # not the empty range of an all-NaN field: an infinite value
            raise PackingError(name, "holds +-inf, which 16-bit simple packing cannot "
                               "represent")
        return PackedField(np.full(flat.size, MISSING_CODE, dtype=np.uint16), 0.0, 0.0)
    codes = np.empty(flat.size, dtype=np.uint16)
    scale = (hi - lo) / MAX_CODE
    _quantise(flat, lo, 1.0 / scale if scale > 0.0 else 0.0, codes)
    return PackedField(codes, lo, scale)


def unpack_field(packed: PackedField, out: np.ndarray | None = None) -> np.ndarray:
    """Decoded float32 values of a packed field (flat), written into `out` when given."""
    codes = np.ascontiguousarray(packed.codes, dtype=np.uint16).reshape(-1)
    if out is None:
        out = np.empty(codes.size, dtype=np.float32)
    elif out.shape != codes.shape or out.dtype != np.float32:
        raise ValueError(f"output array {out.dtype}{out.shape} does not fit {codes.size} "
                         "float32 values")
    _dequantise(codes, float(packed.add_offset), float(packed.scale_factor), out)
    return out



def warm_up() -> None:
    """Load the compiled kernels (numba's first call in a process takes ~0.5 s even from its
    disk cache): the weather node does this at start, not on its first cycle."""
    unpack_field(pack_field(np.array([0.0, 1.0, np.nan], dtype=np.float32)))
