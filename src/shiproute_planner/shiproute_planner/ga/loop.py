"""Seed GA as an ask/tell loop over float arrays (thesis sec. 5.2).

Seeds enter the first population together with jittered copies; the rest is sampled near the
first seed (or the bounds' centre). Each generation: tournament selection on Deb ranks,
crossover (SBX per gene or one-point by stage), structured mutation, and elitist (mu + lambda)
replacement. The caller evaluates what `ask` returns and passes the results to `tell`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np

from .operators import mutate, one_point_by_stage, sbx, tournament
from .ranking import deb_order


@dataclass(frozen=True)
class GAConfig:
    """Seed GA settings. 80 parents and 80 offspring: a smaller elite (30 + 60) converged
    further per evaluation on open-ocean spans, but found a feasible route in none of 18
    storm re-plans where 80 + 80 found 5 (cycle 2 of the March storm, 6,000-10,000
    evaluations), so the wider population stays."""

    pop_size: int = 80
    offspring: int = 80
    tournament_k: int = 2
    p_crossover: float = 0.6
    p_one_point: float = 0.3  # share of crossovers that are one-point by stage
    p_mutation: float = 0.9
    sigma_heading_deg: float = 1.0  # relative headings: a change turns the whole tail
    sigma_rpm: float = 0.7
    jitter_heading_deg: float = 2.0
    jitter_rpm: float = 1.0
    init_spread_heading_deg: float = 6.0


class AskTellGA(Protocol):
    """What the planning loop needs of a GA: `SeedGA` and the `islands.IslandGA` of several."""

    @property
    def pop(self) -> np.ndarray | None: ...  # current population, best first; None at first

    @property
    def best(self) -> tuple[np.ndarray, float, float]: ...  # genes, violation, objective

    @property
    def generation(self) -> int: ...

    @property
    def evaluations(self) -> int: ...

    def ask(self) -> np.ndarray: ...

    def tell(self, x: np.ndarray, violation: np.ndarray, objective: np.ndarray) -> None: ...

    def stalled(self, generations: int, rel_tol: float = 1e-4) -> bool: ...

    def inject(self, x: np.ndarray, violation: np.ndarray, objective: np.ndarray,
               spent: int = 0) -> None: ...


class SeedGA:
    """Ask/tell seed GA on genes in [lower, upper]; reproducible for a given Generator."""

    def __init__(self, lower: np.ndarray, upper: np.ndarray, n_stages: int, config: GAConfig,
                 rng: np.random.Generator, seeds: np.ndarray | None = None) -> None:
        self.lo = np.asarray(lower, dtype=float)
        self.hi = np.asarray(upper, dtype=float)
        self.n = n_stages
        self.cfg = config
        self.rng = rng
        self.seeds = None if seeds is None or len(seeds) == 0 else np.atleast_2d(seeds)
        self.pop: np.ndarray | None = None
        self.pop_v = np.empty(0)
        self.pop_f = np.empty(0)
        self.generation = 0
        self.evaluations = 0
        self.best_history: list[tuple[float, float]] = []

    def _initial(self) -> np.ndarray:
        c, n = self.cfg, self.n
        size = max(c.pop_size, 0 if self.seeds is None else len(self.seeds))
        parts = []
        if self.seeds is not None:
            parts.append(np.clip(self.seeds, self.lo, self.hi))
            base = parts[0]
        else:
            base = 0.5 * (self.lo + self.hi)[None, :]
            base[:, 1:n] = 0.0
        n_left = size - sum(len(p) for p in parts)
        if n_left > 0:
            # seeds arrive best first: half the copies come from the best three
            top = self.rng.integers(0, min(3, len(base)), size=n_left)
            idx = np.where(self.rng.random(n_left) < 0.5, top,
                           self.rng.integers(0, len(base), size=n_left))
            x = base[idx].copy()
            scale = np.linspace(0.3, 3.0, n_left)[:, None]
            x[:, 0] += self.rng.normal(0, c.jitter_heading_deg, n_left) * scale[:, 0]
            x[:, 1:n] += self.rng.normal(0, c.jitter_heading_deg, (n_left, n - 1)) * scale
            x[:, n:] += self.rng.normal(0, c.jitter_rpm, (n_left, 1)) * scale
            x[:, n:] += self.rng.normal(0, 0.5 * c.jitter_rpm, (n_left, n + 1)) * scale
            parts.append(np.clip(x, self.lo, self.hi))
        return np.concatenate(parts, axis=0)

    def ask(self) -> np.ndarray:
        """Genes to evaluate next: the first population, then offspring."""
        if self.pop is None:
            return self._initial()
        c = self.cfg
        order = deb_order(self.pop_v, self.pop_f)
        rank = np.empty(order.size, dtype=np.int64)
        rank[order] = np.arange(order.size)
        m = c.offspring
        pa = self.pop[tournament(rank, m, self.rng, c.tournament_k)]
        pb = self.pop[tournament(rank, m, self.rng, c.tournament_k)]
        cross = self.rng.random(m) < c.p_crossover
        one_pt = self.rng.random(m) < c.p_one_point
        child = pa.copy()
        sel = cross & ~one_pt
        if sel.any():
            child[sel] = sbx(pa[sel], pb[sel], self.lo, self.hi, self.rng)
        sel = cross & one_pt
        if sel.any():
            child[sel] = one_point_by_stage(pa[sel], pb[sel], self.n, self.rng)
        return mutate(child, self.lo, self.hi, self.n, self.rng, c.sigma_heading_deg,
                      c.sigma_rpm, c.p_mutation)

    def tell(self, x: np.ndarray, violation: np.ndarray, objective: np.ndarray) -> None:
        """Merge evaluated genes into the population (elitist mu + lambda)."""
        self.evaluations += len(x)
        if self.pop is None:
            allx, allv, allf = x, violation, objective
        else:
            allx = np.concatenate([self.pop, x])
            allv = np.concatenate([self.pop_v, violation])
            allf = np.concatenate([self.pop_f, objective])
            self.generation += 1
        keep = deb_order(allv, allf)[: self.cfg.pop_size]
        self.pop, self.pop_v, self.pop_f = allx[keep], allv[keep], allf[keep]
        self.best_history.append((float(self.pop_v[0]), float(self.pop_f[0])))

    def inject(self, x: np.ndarray, violation: np.ndarray, objective: np.ndarray,
               spent: int = 0) -> None:
        """Merge genes evaluated outside the loop (a local refinement that cost `spent`
        evaluations, at least one per row) into the population without counting a
        generation."""
        assert self.pop is not None, "tell() has not been called yet"
        self.evaluations += max(spent, len(x))
        allx = np.concatenate([self.pop, x])
        allv = np.concatenate([self.pop_v, violation])
        allf = np.concatenate([self.pop_f, objective])
        keep = deb_order(allv, allf)[: self.cfg.pop_size]
        self.pop, self.pop_v, self.pop_f = allx[keep], allv[keep], allf[keep]
        self.best_history[-1] = (float(self.pop_v[0]), float(self.pop_f[0]))

    @property
    def best(self) -> tuple[np.ndarray, float, float]:
        """Best genes, their violation and objective."""
        assert self.pop is not None, "tell() has not been called yet"
        return self.pop[0], float(self.pop_v[0]), float(self.pop_f[0])

    def stalled(self, generations: int, rel_tol: float = 1e-4) -> bool:
        """True if the best has not improved by `rel_tol` over the last `generations`."""
        h = self.best_history
        if len(h) <= generations:
            return False
        (v0, f0), (v1, f1) = h[-generations - 1], h[-1]
        if v1 > 0 or v0 > 0:
            return False  # keep searching while the best is infeasible
        return f0 - f1 <= rel_tol * abs(f0)
