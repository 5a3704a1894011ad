"""Variation operators on (pop, 2n + 1) gene arrays; every call is vectorised over individuals.

Heading genes are relative, so changing gene k turns the whole tail of the route. Mutation
therefore mixes a *turn* (one gene, tail rotates), a *kink* (+d at k, -d at k + 1: the tail
is shifted, not rotated), a *bend* (a smooth sideways bulge over a window of nodes that
rejoins the track) and smooth RPM perturbations over a window of stages, plus a common RPM
scale that trades fuel against arrival time.
"""

from __future__ import annotations

import numpy as np


def tournament(rank: np.ndarray, n: int, rng: np.random.Generator, k: int = 2) -> np.ndarray:
    """Indices of `n` winners of k-way tournaments; lower `rank` wins."""
    cand = rng.integers(0, rank.size, size=(n, k))
    return cand[np.arange(n), np.argmin(rank[cand], axis=1)]


def sbx(a: np.ndarray, b: np.ndarray, lo: np.ndarray, hi: np.ndarray,
        rng: np.random.Generator, eta: float = 15.0, p_gene: float = 0.5) -> np.ndarray:
    """Simulated binary crossover per gene (Deb & Agrawal 1995), one child per pair."""
    u = rng.random(a.shape)
    beta = np.where(u <= 0.5, (2 * u) ** (1 / (eta + 1)), (1 / (2 * (1 - u))) ** (1 / (eta + 1)))
    sign = np.where(rng.random(a.shape) < 0.5, 1.0, -1.0)
    child = 0.5 * (a + b) + sign * 0.5 * beta * (a - b)
    swap = rng.random(a.shape) < p_gene
    return np.clip(np.where(swap, child, a), lo, hi)


def one_point_by_stage(a: np.ndarray, b: np.ndarray, n_stages: int,
                       rng: np.random.Generator) -> np.ndarray:
    """Child = parent a up to a random stage, parent b from there (headings and RPMs)."""
    pop = a.shape[0]
    cut = (np.asarray(rng.integers(1, n_stages, size=pop))[:, None] if n_stages > 1
           else np.ones((pop, 1), int))
    stage_of_gene = np.concatenate([np.arange(n_stages), np.arange(n_stages + 1)])[None, :]
    return np.where(stage_of_gene < cut, a, b)


def mutate(x: np.ndarray, lo: np.ndarray, hi: np.ndarray, n_stages: int,
           rng: np.random.Generator, sigma_heading_deg: float, sigma_rpm: float,
           p_mutation: float = 0.9) -> np.ndarray:
    """Mutated copy of `x`: each selected individual gets one structured move."""
    x = x.copy()
    pop = x.shape[0]
    n = n_stages
    rows = np.flatnonzero(rng.random(pop) < p_mutation)
    if rows.size == 0:
        return x
    kind = rng.integers(0, 6, size=rows.size)
    k = rng.integers(0, n, size=rows.size)
    d_h = rng.normal(0.0, sigma_heading_deg, size=rows.size)
    # 0: turn (one relative heading); 1: kink (turn at k, turn back at k + 1)
    sel = kind <= 1
    x[rows[sel], k[sel]] += d_h[sel]
    kink = sel & (kind == 1) & (k + 1 < n)
    x[rows[kink], k[kink] + 1] -= d_h[kink]
    # 2: smooth RPM bump over a window of stages
    sel = kind == 2
    if sel.any():
        r = rows[sel]
        centre = rng.integers(0, n + 1, size=r.size)[:, None]
        width = rng.uniform(0.5, 4.0, size=r.size)[:, None]
        stages = np.arange(n + 1)[None, :]
        bump = np.exp(-0.5 * ((stages - centre) / width) ** 2)
        x[r, n:] += rng.normal(0.0, sigma_rpm, size=(r.size, 1)) * bump
    # 3: common RPM scale (earlier/later arrival)
    sel = kind == 3
    if sel.any():
        r = rows[sel]
        x[r, n:] *= 1.0 + rng.normal(0.0, 0.01, size=(r.size, 1)) * sigma_rpm
    # 4: small gaussian noise on every heading gene (path shape) and RPM
    sel = kind == 4
    if sel.any():
        r = rows[sel]
        x[r, :n] += rng.normal(0.0, 0.25 * sigma_heading_deg, size=(r.size, n))
        x[r, n:] += rng.normal(0.0, 0.25 * sigma_rpm, size=(r.size, n + 1))
    # 5: bend: a smooth sideways bulge of the track over a window of nodes that rejoins it,
    # as absolute heading offsets (first difference of the bulge) turned into relative ones
    sel = kind == 5
    if sel.any() and n > 2:
        r = rows[sel]
        centre = rng.uniform(1.0, n - 1.0, size=r.size)[:, None]
        width = rng.uniform(0.7, 4.0, size=r.size)[:, None]
        nodes = np.arange(n + 1)[None, :]
        bulge = np.exp(-0.5 * ((nodes - centre) / width) ** 2)
        offset = rng.normal(0.0, 2.0 * sigma_heading_deg, size=(r.size, 1)) * np.diff(bulge)
        x[r, 0] += offset[:, 0]
        x[r, 1:n] += np.diff(offset, axis=1)
    return np.clip(x, lo, hi)
