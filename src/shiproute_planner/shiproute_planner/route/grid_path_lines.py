"""A grid path made sailable: straight legs between the cells of a shortest path on a
navigable-water grid (`route.passages`), kept where they stay in free water."""

from __future__ import annotations

import numpy as np
from scipy import ndimage


def line_free(free: np.ndarray, a: np.ndarray, b: np.ndarray) -> bool:
    """True when the straight line between two cell centres stays in free cells."""
    n = int(np.ceil(np.abs(b - a).max() * 3.0)) + 1
    t = np.linspace(0.0, 1.0, n + 1)[:, None]
    p = a[None, :] + t * (b - a)[None, :]
    for oi, oj in ((0.0, 0.0), (0.3, 0.3), (-0.3, -0.3), (0.3, -0.3), (-0.3, 0.3)):
        i = np.floor(p[:, 0] + 0.5 + oi).astype(np.int64)
        j = np.floor(p[:, 1] + 0.5 + oj).astype(np.int64)
        i = np.clip(i, 0, free.shape[0] - 1)
        j = np.clip(j, 0, free.shape[1] - 1)
        if not free[i, j].all():
            return False
    return True


def straighten(free: np.ndarray, cells: np.ndarray, max_cells: float) -> np.ndarray:
    """Path vertices kept where the straight line between kept ones would leave free water
    (greedy: from each kept vertex, the farthest next one still in sight, capped in length)."""
    pts = cells.astype(float)
    keep = [0]
    k = 0
    while k < len(pts) - 1:
        nxt = k + 1
        for m in range(k + 2, len(pts)):
            if np.abs(pts[m] - pts[k]).max() > max_cells or not line_free(free, pts[k],
                                                                           pts[m]):
                break
            nxt = m
        keep.append(nxt)
        k = nxt
    return cells[keep]


def sight(free: np.ndarray, unknown: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """Cells a straightened leg may cross: free ones, but water of unknown depth only next
    to the path (straightening must not cut back into what the path kept out of)."""
    if not unknown.any():
        return free
    near = np.zeros(free.shape, dtype=bool)
    near[cells[:, 0], cells[:, 1]] = True
    near = ndimage.binary_dilation(near, iterations=1)
    return free & (~unknown | near)
