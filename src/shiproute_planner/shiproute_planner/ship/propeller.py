"""Wageningen B-series open-water characteristics (KT, KQ polynomials).

Oosterveld, M.W.C. & van Oossanen, P. (1975), "Further computer-analyzed data of the
Wageningen B-screw series", International Shipbuilding Progress 22(251), Re = 2e6 fit:
KT = sum C J^s (P/D)^t (AE/A0)^u Z^v with 39 terms, KQ likewise with 47 terms. The KQ
term (s,t,u,v) = (0,6,2,2) is transcribed in two ways (-4.659e-4 / -4.689e-4); we use
-4.659e-4 as tabulated by Bernitsas, Ray & Kinley (1981, UMich report 237, Table 1).
The difference changes 10KQ by < 3e-4 at B4-70.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

# columns: C, s (J), t (P/D), u (AE/A0), v (Z)
_KT = np.array([
    [0.00880496, 0, 0, 0, 0], [-0.204554, 1, 0, 0, 0], [0.166351, 0, 1, 0, 0],
    [0.158114, 0, 2, 0, 0], [-0.147581, 2, 0, 1, 0], [-0.481497, 1, 1, 1, 0],
    [0.415437, 0, 2, 1, 0], [0.0144043, 0, 0, 0, 1], [-0.0530054, 2, 0, 0, 1],
    [0.0143481, 0, 1, 0, 1], [0.0606826, 1, 1, 0, 1], [-0.0125894, 0, 0, 1, 1],
    [0.0109689, 1, 0, 1, 1], [-0.133698, 0, 3, 0, 0], [0.00638407, 0, 6, 0, 0],
    [-0.00132718, 2, 6, 0, 0], [0.168496, 3, 0, 1, 0], [-0.0507214, 0, 0, 2, 0],
    [0.0854559, 2, 0, 2, 0], [-0.0504475, 3, 0, 2, 0], [0.010465, 1, 6, 2, 0],
    [-0.00648272, 2, 6, 2, 0], [-0.00841728, 0, 3, 0, 1], [0.0168424, 1, 3, 0, 1],
    [-0.00102296, 3, 3, 0, 1], [-0.0317791, 0, 3, 1, 1], [0.018604, 1, 0, 2, 1],
    [-0.00410798, 0, 2, 2, 1], [-0.000606848, 0, 0, 0, 2], [-0.0049819, 1, 0, 0, 2],
    [0.0025983, 2, 0, 0, 2], [-0.000560528, 3, 0, 0, 2], [-0.00163652, 1, 2, 0, 2],
    [-0.000328787, 1, 6, 0, 2], [0.000116502, 2, 6, 0, 2], [0.000690904, 0, 0, 1, 2],
    [0.00421749, 0, 3, 1, 2], [0.0000565229, 3, 6, 1, 2], [-0.00146564, 0, 3, 2, 2],
])
_KQ = np.array([
    [0.00379368, 0, 0, 0, 0], [0.00886523, 2, 0, 0, 0], [-0.032241, 1, 1, 0, 0],
    [0.00344778, 0, 2, 0, 0], [-0.0408811, 0, 1, 1, 0], [-0.108009, 1, 1, 1, 0],
    [-0.0885381, 2, 1, 1, 0], [0.188561, 0, 2, 1, 0], [-0.00370871, 1, 0, 0, 1],
    [0.00513696, 0, 1, 0, 1], [0.0209449, 1, 1, 0, 1], [0.00474319, 2, 1, 0, 1],
    [-0.00723408, 2, 0, 1, 1], [0.00438388, 1, 1, 1, 1], [-0.0269403, 0, 2, 1, 1],
    [0.0558082, 3, 0, 1, 0], [0.0161886, 0, 3, 1, 0], [0.00318086, 1, 3, 1, 0],
    [0.015896, 0, 0, 2, 0], [0.0471729, 1, 0, 2, 0], [0.0196283, 3, 0, 2, 0],
    [-0.0502782, 0, 1, 2, 0], [-0.030055, 3, 1, 2, 0], [0.0417122, 2, 2, 2, 0],
    [-0.0397722, 0, 3, 2, 0], [-0.00350024, 0, 6, 2, 0], [-0.0106854, 3, 0, 0, 1],
    [0.00110903, 3, 3, 0, 1], [-0.000313912, 0, 6, 0, 1], [0.0035985, 3, 0, 1, 1],
    [-0.00142121, 0, 6, 1, 1], [-0.00383637, 1, 0, 2, 1], [0.0126803, 0, 2, 2, 1],
    [-0.00318278, 2, 3, 2, 1], [0.00334268, 0, 6, 2, 1], [-0.00183491, 1, 1, 0, 2],
    [0.000112451, 3, 2, 0, 2], [-0.0000297228, 3, 6, 0, 2], [0.000269551, 1, 0, 1, 2],
    [0.00083265, 2, 0, 1, 2], [0.00155334, 0, 2, 1, 2], [0.000302683, 0, 6, 1, 2],
    [-0.0001843, 0, 0, 2, 2], [-0.000425399, 0, 3, 2, 2], [0.0000869243, 3, 3, 2, 2],
    [-0.0004659, 0, 6, 2, 2], [0.0000554194, 1, 6, 2, 2],
])

KT_TERMS = 39
KQ_TERMS = 47


@dataclass(frozen=True)
class OpenWaterCurve:
    """KT and KQ of one propeller as cubic polynomials in J (coefficients J^0..J^3)."""

    kt_poly: tuple[float, float, float, float]
    kq_poly: tuple[float, float, float, float]

    def kt(self, j: np.ndarray) -> np.ndarray:
        """Thrust coefficient at advance ratio ``j``."""
        a = self.kt_poly
        return a[0] + j * (a[1] + j * (a[2] + j * a[3]))

    def kq(self, j: np.ndarray) -> np.ndarray:
        """Torque coefficient at advance ratio ``j``."""
        a = self.kq_poly
        return a[0] + j * (a[1] + j * (a[2] + j * a[3]))

    def j_zero_thrust(self) -> float:
        """Smallest positive advance ratio where KT reaches zero."""
        roots = np.roots(self.kt_poly[::-1])
        real = sorted(r.real for r in roots if abs(r.imag) < 1e-9 and r.real > 0)
        return float(real[0])


def _collapse(table: np.ndarray, pitch_ratio: float, area_ratio: float, blades: int) -> tuple:
    c = table[:, 0] * pitch_ratio ** table[:, 2] * area_ratio ** table[:, 3] * blades ** table[:, 4]
    return tuple(float(c[table[:, 1] == s].sum()) for s in range(4))


def open_water_curve(pitch_ratio: float, area_ratio: float, blades: int) -> OpenWaterCurve:
    """Reduce the B-series polynomials to cubics in J for a fixed propeller geometry."""
    return OpenWaterCurve(
        kt_poly=_collapse(_KT, pitch_ratio, area_ratio, blades),
        kq_poly=_collapse(_KQ, pitch_ratio, area_ratio, blades),
    )


def kt_kq(
    j: np.ndarray, pitch_ratio: float, area_ratio: float, blades: int
) -> tuple[np.ndarray, np.ndarray]:
    """KT and KQ of a B-series propeller at advance ratios ``j``."""
    curve = open_water_curve(pitch_ratio, area_ratio, blades)
    j = np.asarray(j, dtype=float)
    return curve.kt(j), curve.kq(j)
