"""Fill values of coarse bathymetry compilations: shallow depths that occur far more often
than their neighbours because a compilation set whole unsurveyed shelves to one value.

ETOPO5 (NOAA 1988) is the example: among its sea cells, exactly 10 m occurs 58,872 times and
1 m 26,555 times, against ~4,000-7,000 for 2-9 m and 11-14 m. Such a cell says "shallow
shelf, depth not known", not "10 m": off Santos, Moreton Bay, Mumbai, south of Sicily and in
the Gulf of Suez it reads 10 m where charts show 20-100 m. The values are found from each
file's own histogram (no value is hard-coded), and only in coarse grids (> 1 arc-minute).
"""

from __future__ import annotations

import numpy as np

SHALLOW_M = 50  # fill values are looked for among whole-metre depths down to this
EXCESS = 3.0  # a value this many times as frequent as the median of its +-3 m neighbours
MIN_CELLS = 1000  # ... and at least this frequent (a pattern of the file, not one bank)


def shelf_fill_values(depth_m: np.ndarray) -> np.ndarray:
    """Whole-metre depths (1..SHALLOW_M m) the grid holds far more often than their
    neighbours (see the module docstring); empty when none."""
    d = np.asarray(depth_m, dtype=np.float64)
    d = d[np.isfinite(d) & (d > 0.5) & (d <= SHALLOW_M + 3.5)]
    whole = d[np.abs(d - np.round(d)) < 1e-3]
    counts = np.bincount(np.round(whole).astype(np.int64), minlength=SHALLOW_M + 4)
    out = []
    for v in range(1, SHALLOW_M + 1):
        near = [counts[k] for k in range(v - 3, v + 4) if k != v and 1 <= k < counts.size]
        ref = float(np.median(near)) if near else 0.0
        if counts[v] >= MIN_CELLS and counts[v] >= EXCESS * max(ref, 1.0):
            out.append(float(v))
    return np.array(out)
