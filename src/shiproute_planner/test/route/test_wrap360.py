"""The compiled kernels' degree wrap (`geo.angle_kernels.wrap360`) is Python's `x % 360.0` bit
for bit, signed zeros and the round-up to 360.0 of tiny negative values included."""

from __future__ import annotations

import math

import numpy as np
from shiproute_planner.geo import angle_kernels as fk


def _bits(x: float) -> bytes:
    return np.float64(x).tobytes()


def test_wrap360_is_python_modulo_bit_for_bit():
    rng = np.random.default_rng(1)
    edges = [0.0, -0.0, 360.0, -360.0, 720.0, -720.0, 359.99999999999994, 1e-300, -1e-300,
             -1e-14, -5e-324, 719.9999999999999, 360.00000000000006, -359.99999999999994,
             1e17, -1e17, math.inf, -math.inf, math.nan, 180.0, -180.0, 540.0]
    values = np.concatenate([edges, rng.uniform(-1000.0, 1000.0, 20_000),
                             rng.uniform(-360.0, 720.0, 20_000) * 1e-12,
                             np.nextafter(np.array([0.0, 360.0, 720.0, -360.0] * 2),
                                          np.array([-1.0, 1.0] * 4))])
    for x in values:
        got, want = fk.wrap360(float(x)), float(x) % 360.0
        assert _bits(got) == _bits(want) or (math.isnan(got) and math.isnan(want)), x
    assert _bits(fk.wrap360(-1e-14)) == _bits(360.0)  # Python rounds it up to 360 too
    assert _bits(fk.wrap360(-0.0)) == _bits(0.0)
