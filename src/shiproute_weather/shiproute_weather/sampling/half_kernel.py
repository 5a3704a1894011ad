"""Numba kernels for the sampler's half-precision storage: float32 -> IEEE 754 binary16 bits.

numba has no float16 type on the CPU, so half-precision fields are held as uint16 bit patterns:
written (rounded to nearest, ties to even, exactly as numpy's ``astype(np.float16)``) by the
packing kernel (`pack_kernel`: by the CPU's conversion instruction, or by `half_bits` here
where there is none) and read back through `HALF_TO_FLOAT32`.
"""

from __future__ import annotations

import numpy as np
from numba import njit

#: float32 value of every binary16 bit pattern (NaN patterns stay NaN)
HALF_TO_FLOAT32 = np.arange(65536, dtype=np.uint16).view(np.float16).astype(np.float32)


@njit(cache=True, nogil=True, inline="always")
def half_bits(b: np.uint32) -> np.uint32:
    """binary16 bit pattern of the float32 with bit pattern `b`; beyond +-65504 -> +-inf."""
    sign = (b >> np.uint32(16)) & np.uint32(0x8000)
    u = b & np.uint32(0x7FFFFFFF)
    if u >= np.uint32(0x38800000):  # normal binary16 range from 2^-14 up
        if u > np.uint32(0x7F800000):
            h = np.uint32(0x7E00)  # NaN
        elif u >= np.uint32(0x477FF000):
            h = np.uint32(0x7C00)  # rounds to beyond 65504: inf
        else:  # re-bias the exponent (127 -> 15), round the 13 dropped bits to even
            h = (u - np.uint32(0x38000000) + np.uint32(0xFFF)
                 + ((u >> np.uint32(13)) & np.uint32(1))) >> np.uint32(13)
    elif u < np.uint32(0x33000000):  # below 2^-25: rounds to zero
        h = np.uint32(0)
    else:  # subnormal binary16: the value in steps of 2^-24
        shift = np.uint32(126) - (u >> np.uint32(23))  # 14..24
        m = (u & np.uint32(0x7FFFFF)) | np.uint32(0x800000)
        h = m >> shift
        rem = m & ((np.uint32(1) << shift) - np.uint32(1))
        tie = np.uint32(1) << (shift - np.uint32(1))
        if rem > tie or (rem == tie and (h & np.uint32(1))):
            h += np.uint32(1)
    return sign | h


@njit(cache=True, nogil=True)
def float32_to_half_bits(src_bits: np.ndarray, dst: np.ndarray) -> None:
    """dst[i] = binary16 bits of the float32 with bits src_bits[i] (`values.view(np.uint32)`)."""
    for i in range(src_bits.shape[0]):
        dst[i] = half_bits(np.uint32(src_bits[i]))
