"""Numba kernel packing forecast fields into the sampler's half-precision channel-last array.

One pass per slice: every field, float32 values or 16-bit wire codes (`wire_packing`), is
decoded, directions [deg] become sine and cosine, and each channel is rounded to IEEE binary16
(bit-exact with numpy's ``astype(np.float16)`` of the float32 value) into the (point, channel)
destination. Work goes in blocks of `BLOCK` points: each channel is converted into a
contiguous row (SIMD), then the rows are interleaved into the destination, four channels per
64-bit store, while they are still in L1 cache.

Sources are passed as addresses (int64) rather than a tuple of arrays: numba indexes a tuple
by a run-time position through a copy of the whole tuple, which cost more than the conversion
itself; the caller keeps the arrays alive for the call.

Sine and cosine are computed in float32 without branches: the angle is reduced in degrees
(deg - 90 k is exact for a float32 angle, so the error stays relative next to multiples of
90 deg) and the polynomials below are within 4e-9 of sine and cosine on |r| <= pi/4. The
float32 result is within a few float32 ulps of the exact value (numpy's own float32 sin/cos
are within 1 ulp of sin/cos of the float32-rounded radians); after rounding to half
precision, |error| <= (2^-11 + 2^-21) |value| + 2^-25, and a rare value differs from numpy's
by one half-precision step.
"""

from __future__ import annotations

import numpy as np
from llvmlite import ir
from numba import carray, njit, types
from numba.extending import intrinsic

from .half_kernel import half_bits

#: points per block
BLOCK = 256
#: field kinds: bit 0 set for wire codes (else float32 values), bit 1 set for a direction
#: (two channels: sine, cosine; else one channel, the value)
F32_SCALAR, CODES_SCALAR, F32_DIRECTION, CODES_DIRECTION = 0, 1, 2, 3

_F = np.float32
_DEG = _F(np.pi / 180.0)
_INV90, _NINETY = _F(1.0 / 90.0), _F(90.0)
_HALF, _ONE, _TWO, _FOUR, _QUARTER = _F(0.5), _F(1.0), _F(2.0), _F(4.0), _F(0.25)
# near-minimax fits on |r| <= pi/4 (Lawson-weighted least squares; relative error 3.8e-9
# for the sine, 1.2e-10 for the cosine, below float32's 6e-8):
#   sin r = r + r^3 (S3 + z (S5 + z S7)),  cos r = 1 - z/2 + z^2 (C4 + z (C6 + z C8)), z = r^2
_S3, _S5, _S7 = _F(-0.16666655242443085), _F(0.00833216030150652), _F(-0.0001951521699083969)
_C4, _C6, _C8 = _F(0.04166664555668831), _F(-0.0013887315290048718), _F(2.4433080398011953e-05)


@intrinsic
def _bits(typingctx, x):
    """Bit pattern (uint32) of a float32 scalar: a register move, no memory round trip."""
    if x != types.float32:
        return None

    def codegen(context, builder, signature, args):
        return builder.bitcast(args[0], ir.IntType(32))

    return types.uint32(types.float32), codegen


@intrinsic
def _fptrunc_half(typingctx, x):
    """binary16 bits of a float32 by LLVM's fptrunc (x86 F16C vcvtps2ph, AArch64 fcvt)."""
    if x != types.float32:
        return None

    def codegen(context, builder, signature, args):
        return builder.bitcast(builder.fptrunc(args[0], ir.HalfType()), ir.IntType(16))

    return types.uint16(types.float32), codegen


def _pointer_intrinsic(dtype: types.Number):
    ptr = types.CPointer(dtype)

    @intrinsic
    def at(typingctx, address):
        if not isinstance(address, types.Integer):
            return None

        def codegen(context, builder, signature, args):
            return builder.inttoptr(args[0], context.get_value_type(ptr))

        return ptr(address), codegen

    return at


_f32_at = _pointer_intrinsic(types.float32)
_u16_at = _pointer_intrinsic(types.uint16)


def _hardware_half() -> bool:
    """Whether this CPU converts float32 to binary16 in hardware (elsewhere LLVM would call a
    run-time helper that numba may not link)."""
    from llvmlite import binding

    triple = binding.get_process_triple()
    if triple.startswith(("x86_64", "i686", "i386")):
        return bool(binding.get_host_cpu_features().get("f16c", False))
    return triple.startswith(("aarch64", "arm64"))


@njit(cache=True, nogil=True, inline="always")
def decode(code: np.uint16, offset: float, scale: float) -> np.float32:
    """float32 value of a wire code (`wire_packing`): float32(offset + scale * code) computed
    in float64; 65535 -> NaN."""
    v = np.float32(offset + scale * np.float64(code))
    return np.float32(np.nan) if code == 65535 else v


if _hardware_half():
    @njit(cache=True, nogil=True, inline="always")
    def half_of(x: np.float32) -> np.uint16:
        """binary16 bits of a float32, rounded to nearest even (numpy's astype(float16))."""
        return _fptrunc_half(x)  # type: ignore[call-arg]  # numba passes the typing context
else:  # pragma: no cover - x86-64 CPUs have F16C since 2012
    @njit(cache=True, nogil=True, inline="always")
    def half_of(x: np.float32) -> np.uint16:
        """binary16 bits of a float32, rounded to nearest even (numpy's astype(float16))."""
        return np.uint16(half_bits(_bits(x)))  # type: ignore[call-arg]  # as above


@njit(cache=True)
def address(a: np.ndarray) -> int:
    """Memory address of an array's first element (a quarter of ``a.ctypes.data``'s cost).
    Keeps the GIL: releasing it for a few nanoseconds of work would cost a wait for it back
    (up to the 5 ms switch interval) while a ROS executor thread runs Python."""
    return a.ctypes.data


@njit(cache=True, nogil=True, inline="always")
def sin_cos_deg(deg: np.float32) -> tuple[np.float32, np.float32]:
    """float32 (sin, cos) of a float32 angle in degrees (|deg| < 2^23), branch-free."""
    k = np.floor(deg * _INV90 + _HALF)
    r = (deg - _NINETY * k) * _DEG  # |r| <= pi/4 (+ a float32 rounding)
    z = r * r
    s = r + r * z * (_S3 + z * (_S5 + z * _S7))
    c = _ONE - _HALF * z + z * z * (_C4 + z * (_C6 + z * _C8))
    # rotate (s, c) by q * 90 deg, q = k mod 4, by exact float arithmetic (of the two products
    # one is 0, the other 1 * value): branches would mispredict on random directions
    q = k - _FOUR * np.floor(k * _QUARTER)
    swap = q - _TWO * np.floor(q * _HALF)  # q odd: sine and cosine trade places
    sign_sin = _ONE - _TWO * np.floor(q * _HALF)  # - for q = 2, 3
    q1 = q + _ONE - _FOUR * np.floor((q + _ONE) * _QUARTER)
    sign_cos = _ONE - _TWO * np.floor(q1 * _HALF)  # - for q = 1, 2
    return (sign_sin * (s * (_ONE - swap) + c * swap),
            sign_cos * (c * (_ONE - swap) + s * swap))


@njit(cache=True, nogil=True)
def _values_row(src: np.ndarray, row: np.ndarray) -> None:
    for i in range(src.shape[0]):
        row[i] = half_of(src[i])


@njit(cache=True, nogil=True)
def _codes_row(cod: np.ndarray, offset: float, scale: float, row: np.ndarray) -> None:
    for i in range(cod.shape[0]):
        row[i] = half_of(decode(cod[i], offset, scale))


@njit(cache=True, nogil=True)
def _decode_into(cod: np.ndarray, offset: float, scale: float, out: np.ndarray) -> None:
    for i in range(cod.shape[0]):
        out[i] = decode(cod[i], offset, scale)


@njit(cache=True, nogil=True)
def _direction_rows(deg: np.ndarray, row_sin: np.ndarray, row_cos: np.ndarray) -> None:
    for i in range(deg.shape[0]):
        s, c = sin_cos_deg(deg[i])
        row_sin[i] = half_of(s)
        row_cos[i] = half_of(c)


@njit(cache=True, nogil=True)
def _interleave4(rows: np.ndarray, m: int, dst64: np.ndarray) -> None:
    """dst64[i, g] = channels 4g..4g+3 of point i as one 64-bit word (little endian)."""
    for g in range(dst64.shape[1]):
        r0, r1, r2, r3 = rows[4 * g], rows[4 * g + 1], rows[4 * g + 2], rows[4 * g + 3]
        for i in range(m):
            dst64[i, g] = (np.uint64(r0[i]) | (np.uint64(r1[i]) << np.uint64(16))
                           | (np.uint64(r2[i]) << np.uint64(32))
                           | (np.uint64(r3[i]) << np.uint64(48)))


@njit(cache=True, nogil=True)
def _interleave1(rows: np.ndarray, m: int, dst: np.ndarray) -> None:
    for c in range(dst.shape[1]):
        r = rows[c]
        for i in range(m):
            dst[i, c] = r[i]


@njit(cache=True, nogil=True)
def pack_half_channels(addresses: np.ndarray, kinds: np.ndarray, offsets: np.ndarray,
                       scales: np.ndarray, dst: np.ndarray) -> None:
    """Write field k into dst[:, c] (a scalar) or dst[:, c:c+2] (sine, cosine of a direction),
    fields in order. Field k is dst.shape[0] float32 values (F32_*) or uint16 wire codes
    (CODES_*, decoded with offsets[k], scales[k]) starting at addresses[k]; dst: (points,
    channels) uint16 binary16 bits, C-contiguous."""
    n, n_ch = dst.shape
    rows = np.empty((n_ch, BLOCK + 32), dtype=np.uint16)  # padded: rows not 512 B apart
    deg = np.empty(BLOCK, dtype=np.float32)
    wide = n_ch % 4 == 0
    if wide:  # rows of 4k channels: 64-bit aligned words
        dst64 = dst.reshape(-1).view(np.uint64).reshape(n, n_ch // 4)
    else:
        dst64 = np.empty((0, 1), dtype=np.uint64)
    for p0 in range(0, n, BLOCK):
        m = min(BLOCK, n - p0)
        c = 0
        for k in range(kinds.shape[0]):
            kind = kinds[k]
            if kind & 1:
                cod = carray(_u16_at(addresses[k] + 2 * p0), (m,))
            else:
                src = carray(_f32_at(addresses[k] + 4 * p0), (m,))
            if kind == F32_SCALAR:
                _values_row(src, rows[c, :m])
                c += 1
            elif kind == CODES_SCALAR:
                _codes_row(cod, offsets[k], scales[k], rows[c, :m])
                c += 1
            else:
                if kind == CODES_DIRECTION:
                    _decode_into(cod, offsets[k], scales[k], deg[:m])
                    src = deg[:m]
                _direction_rows(src, rows[c, :m], rows[c + 1, :m])
                c += 2
        if wide:
            _interleave4(rows, m, dst64[p0:p0 + m])
        else:
            _interleave1(rows, m, dst[p0:p0 + m])
